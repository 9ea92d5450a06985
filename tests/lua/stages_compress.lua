-- Test: the init + compress stages on a small tissue (8 adipocytes, 400 cancer cells)
-- reach the target packing fraction within 1e-3, leave every site force below the final
-- tolerance, keep each adipocyte's volume within 1 % of its reference, and keep the two
-- populations de-mixed with a planar interface. De-mixed here means: the cancer cells as a
-- slab are left of the adipocytes (their mean x is below the leftmost adipocyte centre) and
-- no cancer cell lies behind an adipocyte. The slab's surface follows the first layer of
-- adipocytes, so cells may fill the grooves between them (about one adipocyte radius deep);
-- a cell is behind adipocyte b when b's centre is left of it and within half the outer
-- radius (1.5 sigma) of it in the periodic y-z plane, i.e. well inside b's shadow on the
-- wall. A cell in a groove between touching adipocytes stays about one outer radius
-- (2.5-3 sigma) from their centres in y-z. The same criterion in tests/unit/test_setup.cpp
-- is checked to flag a packing with the cells spread among the adipocytes.
package.path = "../../protocols/?.lua;" .. package.path
local iv = require("invasim")
local p = iv.params{ seed = 1, phi = 0.72 }

local tissue = require("lib.init"){ N_a = 8, N_c = 400, L0 = 46.0, seed = p.seed }
local report = require("lib.compress")(tissue, { to_phi = p.phi, final_ftol = 1e-6, progress = false })
local sys = tissue.sys

local function check(ok, fmt, ...)
  local msg = string.format(fmt, ...)
  if not ok then error("FAILED: " .. msg, 2) end
  print("ok: " .. msg)
end

local phi = sys:packing().total
check(math.abs(phi - p.phi) < 1e-3, "phi = %.6f within 1e-3 of %.2f", phi, p.phi)
check(report.converged and report.max_force < 1e-6, "max force %.3e < 1e-6 (converged: %s)",
      report.max_force, tostring(report.converged))
-- The force reported by the stage is the engine's: re-evaluate independently.
local fire = iv.Fire{ ftol = 1e-6, max_steps = 0 }:minimize(sys)
check(fire.max_force < 1e-6, "re-evaluated max force %.3e < 1e-6", fire.max_force)

local adipocytes = sys:adipocytes()
local worst = 0
for _, a in ipairs(adipocytes) do
  worst = math.max(worst, math.abs(a.volume / a.ref_volume - 1))
end
check(worst < 0.01, "largest adipocyte volume deviation %.3e < 1 %%", worst)

local mean_cell_x = 0
local cells = sys:positions(tissue.cells)
for _, r in ipairs(cells) do mean_cell_x = mean_cell_x + r[1] / #cells end
local box = sys:box()
local L = box.lengths[1]
local min_centre_x = math.huge
for _, a in ipairs(adipocytes) do min_centre_x = math.min(min_centre_x, a.centre[1]) end
check(mean_cell_x < min_centre_x, "de-mixed: mean cancer-cell x = %.3f < leftmost adipocyte centre X = %.3f",
      mean_cell_x, min_centre_x)

-- Periodic y-z distance between a cell and an adipocyte centre.
local function yz_distance(r, c)
  local d2 = 0
  for k = 2, 3 do
    local d = r[k] - c[k]
    local l = box.lengths[k]
    d = d - l * math.floor(d / l + 0.5)
    d2 = d2 + d * d
  end
  return math.sqrt(d2)
end
local closest, closest_x, closest_X = math.huge, nil, nil
for _, r in ipairs(cells) do
  for _, a in ipairs(adipocytes) do
    if a.centre[1] < r[1] then
      local d = yz_distance(r, a.centre)
      if d < closest then closest, closest_x, closest_X = d, r[1], a.centre[1] end
    end
  end
end
check(closest >= 1.5, "planar interface: no cell behind an adipocyte (closest: y-z distance %.3f >= 1.5, cell x %s, centre X %s; box %.3f)",
      closest, tostring(closest_x), tostring(closest_X), L)
print(string.format("box L_f = %.4f, compression steps %d, FIRE iterations %d", L, report.steps,
                    report.fire_steps))
