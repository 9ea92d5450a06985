-- Test: with the protocols' default vertex bath, passive cancer cells and adipocyte
-- vertices equilibrate: T_c/T_a = 1 within 2 % on the reduced system (8 adipocytes, 400
-- cells) at k_B T = 0.3 P sigma^3 (the paper: "for the passive model, T_c and T_a
-- equilibrate"). The mean of T_c/T_a over the production has an error well
-- below 2 % (asserted < 0.5 %); the piston's bath is the vertices'. With --set
-- vertex_bath=damped --set vertex_gamma=0.2 (the protocols' earlier default bath) it fails:
-- T_c/T_a is about 20.
package.path = "../../protocols/?.lua;" .. package.path
local iv = require("invasim")
local decl = require("lib.parameters").declarations()
local preset = require("lib.presets").reduced
local p = iv.params{
  vertex_bath = decl.vertex_bath[1], vertex_gamma = decl.vertex_gamma[1],
  vertex_mass = decl.vertex_mass[1], vertex_kT = decl.vertex_kT[1], seed = 3,
  kT = 3.9e-4, quench_steps = 10000, steps = 40000, every = 50,
}

local tissue = require("lib.init"){ N_a = preset.N_a, N_c = preset.N_c, L0 = preset.L0, seed = p.seed }
require("lib.compress")(tissue, { to_phi = 0.72, progress = false })
require("lib.quench")(tissue, { P = 1.3e-3, kT = p.kT, f0 = 0.0, vertex_bath = p.vertex_bath,
                                vertex_gamma = p.vertex_gamma, vertex_mass = p.vertex_mass,
                                vertex_kT = p.vertex_kT, steps = p.quench_steps,
                                progress = false })
-- The piston shares the vertices' bath: noise at kT with langevin vertices, none with damped.
local piston_kT = tissue.dyn:wall_state().kT
assert(piston_kT == (p.vertex_bath == "langevin" and p.kT or 0),
       string.format("FAILED: the piston's kT = %g with %s vertices at kT = %g", piston_kT, p.vertex_bath, p.kT))
local result = require("lib.production")(tissue, {
  steps = p.steps, every = p.every, average_fraction = 1.0, interface = false,
  correlate_every = 0, slices_per_body = 0, progress = false,
})
local r = result.summary.T_c_over_T_a
print(string.format("vertex_bath = %s, vertex_gamma = %g, vertex_mass = %g: T_c/T_a = %.4f +- %.4f (%d samples), T_c/kT = %.4f",
                    p.vertex_bath, p.vertex_gamma, p.vertex_mass, r.mean, r.error, r.samples,
                    result.summary.T_c.mean / p.kT))
assert(math.abs(r.mean - 1) < 0.02, string.format("FAILED: T_c/T_a = %.4f is not 1 within 2 %%", r.mean))
assert(r.error > 0 and r.error < 0.005, "FAILED: the error bar " .. r.error .. " is not well below 2 %")
print("ok: passive T_c/T_a = 1 within 2 %")
