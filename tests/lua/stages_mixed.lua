-- Test: the protocols' `start` and `A_0` parameters reach the engine through
-- lib/parameters.lua and the init and compress stages. Run with --set start=mixed --set A_0=1.3 (and a small system): every
-- adipocyte's reference shape parameter is A_0, the compression of the mixed start reaches
-- phi, and the packing is genuinely mixed: it fails both de-mixing criteria of
-- stages_compress.lua (the cells' mean x is right of the leftmost adipocyte centre, and
-- cells lie behind adipocytes, within 1.5 sigma of a centre left of them in y-z).
package.path = "../../protocols/?.lua;" .. package.path
local iv = require("invasim")
local parameters = require("lib.parameters")
local stage = require("lib.stages")
local p = iv.params(parameters.merge{})
parameters.validate(p)
local N_a, N_c, L0 = parameters.size(p)
local tissue = stage.init{ N_a = N_a, N_c = N_c, L0 = L0, seed = p.seed, start = p.start,
                           shape_param = p.A_0, eps_v = p.eps_v, eps_a = p.eps_a,
                           alpha = p.alpha, beta = p.beta }
stage.compress(tissue, { to_phi = p.phi, ftol = p.compress_ftol, final_ftol = p.final_ftol })
local sys = tissue.sys

local function check(ok, fmt, ...)
  local msg = string.format(fmt, ...)
  if not ok then error("FAILED: " .. msg, 2) end
  print("ok: " .. msg)
end

local adipocytes = sys:adipocytes()
local worst = 0
for _, a in ipairs(adipocytes) do worst = math.max(worst, math.abs(a.ref_shape_parameter - p.A_0)) end
check(#adipocytes > 0 and worst < 1e-9, "reference shape parameter of all %d adipocytes = A_0 = %g (largest deviation %.1e)",
      #adipocytes, p.A_0, worst)
local phi = sys:packing().total
check(math.abs(phi - p.phi) < 1e-3, "%s start compressed to phi = %.4f (target %g)", p.start, phi, p.phi)

local cells = sys:positions(tissue.cells)
local mean_cell_x = 0
for _, r in ipairs(cells) do mean_cell_x = mean_cell_x + r[1] / #cells end
local min_centre_x = math.huge
for _, a in ipairs(adipocytes) do min_centre_x = math.min(min_centre_x, a.centre[1]) end
local box = sys:box()
local behind = 0
for _, r in ipairs(cells) do
  for _, a in ipairs(adipocytes) do
    local d2 = 0
    for k = 2, 3 do
      local d = r[k] - a.centre[k]
      d = d - box.lengths[k] * math.floor(d / box.lengths[k] + 0.5)
      d2 = d2 + d * d
    end
    if a.centre[1] < r[1] and d2 < 1.5 * 1.5 then behind = behind + 1; break end
  end
end
local mixed = mean_cell_x > min_centre_x and behind > 0
print(string.format("packing is %s: mean cell x %.3f, leftmost adipocyte centre %.3f, %d of %d cells behind an adipocyte",
                    mixed and "mixed" or "de-mixed", mean_cell_x, min_centre_x, behind, #cells))
