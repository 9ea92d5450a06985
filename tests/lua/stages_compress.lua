-- Issue 3 test: the init + compress stages on a small tissue (8 adipocytes, 400 cancer cells)
-- reach the target packing fraction within 1e-3, leave every site force below the final
-- tolerance, keep each adipocyte's volume within 1 % of its reference, and keep the two
-- populations de-mixed with a planar interface. De-mixed here means: the cancer cells as a
-- slab are left of the adipocytes (their mean x is below the leftmost adipocyte centre) and
-- no cancer cell got past the first layer of adipocytes (every cell x < leftmost adipocyte
-- centre + its outer radius 3): the interface is rough only on the scale of one adipocyte.
-- A mixed packing (cells spread through the box, L_f ~ 11) fails both.
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

local worst = 0
for _, a in ipairs(sys:adipocytes()) do
  worst = math.max(worst, math.abs(a.volume / a.ref_volume - 1))
end
check(worst < 0.01, "largest adipocyte volume deviation %.3e < 1 %%", worst)

local max_cell_x, mean_cell_x = -math.huge, 0
local cells = sys:positions(tissue.cells)
for _, r in ipairs(cells) do
  max_cell_x = math.max(max_cell_x, r[1])
  mean_cell_x = mean_cell_x + r[1] / #cells
end
local L = sys:box().lengths[1]
local min_centre_x, max_centre_x = math.huge, -math.huge
for _, a in ipairs(sys:adipocytes()) do
  min_centre_x = math.min(min_centre_x, a.centre[1])
  max_centre_x = math.max(max_centre_x, a.centre[1])
end
check(mean_cell_x < min_centre_x, "de-mixed: mean cancer-cell x = %.3f < leftmost adipocyte centre X = %.3f",
      mean_cell_x, min_centre_x)
check(max_cell_x < min_centre_x + 3, "planar interface: rightmost cancer cell x = %.3f < leftmost adipocyte centre + 3 = %.3f (box %.3f)",
      max_cell_x, min_centre_x + 3, L)
print(string.format("box L_f = %.4f, compression steps %d, FIRE iterations %d", L, report.steps,
                    report.fire_steps))
