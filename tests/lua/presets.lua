-- Test: the system presets (protocols/lib/presets.lua). "paper" is the paper's standard system
-- (docs/model.md, protocol step 1: L_0 = 70, N_a = 28, N_c = 1500), "large" its larger one
-- (N_a = 128, N_c = 7000), and all three start at the paper's initial packing fraction
-- (~0.01: cells of diameters 0.9 and 1.1 half each, adipocytes of diameter 6, in L_0^3);
-- --set system=NAME reaches them through lib.parameters.size, and N_a, N_c, L0 override them.
package.path = "../../protocols/?.lua;" .. package.path
local presets = require("lib.presets")
local parameters = require("lib.parameters")

local function phi0(t)
  local cell = math.pi / 6 * 0.5 * (0.9 ^ 3 + 1.1 ^ 3)
  local adipocyte = math.pi / 6 * 6 ^ 3
  return (t.N_c * cell + t.N_a * adipocyte) / t.L0 ^ 3
end
local paper, large, reduced = presets.paper, presets.large, presets.reduced
assert(paper.N_a == 28 and paper.N_c == 1500 and paper.L0 == 70, "paper: the paper's 28, 1500, 70")
assert(large.N_a == 128 and large.N_c == 7000, "large: the paper's 128, 7000")
assert(phi0(paper) > 0.009 and phi0(paper) < 0.013, "paper's phi_0 = " .. phi0(paper))
for name, t in pairs{ reduced = reduced, large = large } do
  assert(math.abs(phi0(t) / phi0(paper) - 1) < 0.05,
         string.format("%s: phi_0 = %.4f, the paper's %.4f", name, phi0(t), phi0(paper)))
end
for name, t in pairs(presets) do
  local N_a, N_c, L0 = parameters.size{ system = name, N_a = 0, N_c = 0, L0 = 0 }
  assert(N_a == t.N_a and N_c == t.N_c and L0 == t.L0, "size of " .. name)
end
local N_a, N_c, L0 = parameters.size{ system = "paper", N_a = 4, N_c = 60, L0 = 32 }
assert(N_a == 4 and N_c == 60 and L0 == 32, "N_a, N_c and L0 override the preset")
print(string.format("presets: ok (phi_0 = %.4f paper, %.4f reduced, %.4f large)", phi0(paper),
                    phi0(reduced), phi0(large)))
