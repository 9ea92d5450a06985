-- Test: the compress stage's FIRE time step (lib/compress.lua, default_dt_max). With
-- adipocytes, dt_max defaults to 0.15 sqrt(1e3 / eps_v): below the stability limit of the
-- meshes' volume mode, so FIRE does not grow its step into that instability and reset over
-- and over. The same small tissue compressed with the engine's dt_max (0.5, the stage's
-- default before) needs several times more FIRE iterations; both end converged at phi.
-- The stage logs the dt_max it uses (checked by the CTest EXPECT: 0.15, 0.075 at eps_v = 4e3,
-- and an explicit dt_max as given).
package.path = "../../protocols/?.lua;" .. package.path
local iv = require("invasim")

local function check(ok, fmt, ...)
  local msg = string.format(fmt, ...)
  if not ok then error("FAILED: " .. msg, 2) end
  print("ok: " .. msg)
end

-- Compresses a fresh small tissue (2 adipocytes, 200 cells: with fewer, each adipocyte would
-- reach across the box to its own periodic image) with the stage; returns the FIRE
-- iterations of the compression steps and the final FIRE, and the final phi and max force.
local function compress(eps_v, dt_max)
  local tissue = require("lib.init"){ N_a = 2, N_c = 200, L0 = 26.0, seed = 1, eps_v = eps_v }
  local r = require("lib.compress")(tissue, { to_phi = 0.72, progress = false, dt_max = dt_max })
  return r.fire_steps + r.final.steps, tissue.sys:packing().total, r
end

local fast, phi_fast, r_fast = compress(1e3, nil)
local slow, phi_slow, r_slow = compress(1e3, iv.Fire.defaults.dt_max)
for _, c in ipairs{ { "default dt_max", phi_fast, r_fast }, { "engine dt_max", phi_slow, r_slow } } do
  check(math.abs(c[2] - 0.72) < 1e-3 and c[3].converged and c[3].max_force < 1e-6,
        "%s: phi = %.4f, converged, max force %.2e < 1e-6", c[1], c[2], c[3].max_force)
end
check(3 * fast < slow, "FIRE iterations with the stage's dt_max: %d, with the engine's 0.5: %d (over 3x more)",
      fast, slow)
-- A stiffer volume term gets a smaller step (logged), and still converges.
local stiff, phi_stiff, r_stiff = compress(4e3, nil)
check(r_stiff.converged and math.abs(phi_stiff - 0.72) < 1e-3,
      "eps_v = 4e3: converged at phi = %.4f in %d FIRE iterations", phi_stiff, stiff)
print("stages_compress_fire: all checks passed")
