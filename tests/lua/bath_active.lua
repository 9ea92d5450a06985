-- Test: with the protocols' default vertex bath and background (docs/model.md, "Vertex bath"),
-- active cohesive cells (tau_p = 25, beta = 1e-2, f0 = 0.0045: 2 k_B T_c/(P sigma^3) ~ 0.9,
-- inside the range of the paper's Fig. 5) keep the paper's 1 < T_c/T_a < 1.2 on the reduced
-- system: the mean of T_c/T_a over the production, +- 2 block-averaging errors, lies inside the
-- window. With --set background_factor=0 (no background: damped vertices) it fails, T_c/T_a
-- is about 4.
package.path = "../../protocols/?.lua;" .. package.path
local iv = require("invasim")
local decl = require("lib.parameters").declarations()
local motion = require("lib.motion")
local preset = require("lib.presets").reduced
local p = iv.params{
  vertex_bath = decl.vertex_bath[1], vertex_gamma = decl.vertex_gamma[1],
  vertex_mass = decl.vertex_mass[1], vertex_kT = decl.vertex_kT[1],
  background_factor = decl.background_factor[1], kT = decl.kT[1], f0 = 0.0045, tau_p = 25.0,
  gamma = decl.gamma[1], beta = 1e-2, P = 1.3e-3, dt = decl.dt[1], seed = 3,
  quench_steps = 20000, steps = 40000, every = 100,
}

local tissue = require("lib.init"){ N_a = preset.N_a, N_c = preset.N_c, L0 = preset.L0,
                                    seed = p.seed, beta = p.beta }
require("lib.compress")(tissue, { to_phi = 0.72, progress = false })
require("lib.quench")(tissue, motion.quench_options(p, { steps = p.quench_steps, progress = false }))
local result = require("lib.production")(tissue, {
  steps = p.steps, every = p.every, average_fraction = 1.0, interface = false,
  correlate_every = 0, slices_per_body = 0, progress = false,
})
local r = result.summary.T_c_over_T_a
local x = 2 * result.summary.T_c.mean / p.P
print(string.format("background_factor = %g, vertex_bath = %s: T_c/T_a = %.4f +- %.4f (%d samples), 2 k_B T_c/(P sigma^3) = %.3g",
                    p.background_factor, p.vertex_bath, r.mean, r.error, r.samples, x))
assert(r.error > 0 and r.error < 0.02, "FAILED: the error bar " .. r.error .. " is too wide to test the window")
assert(r.mean - 2 * r.error > 1.0 and r.mean + 2 * r.error < 1.2,
       string.format("FAILED: T_c/T_a = %.4f +- %.4f is not inside (1, 1.2)", r.mean, r.error))
assert(x > 0.1 and x < 3, string.format("FAILED: 2 k_B T_c/(P sigma^3) = %.3g is outside Fig. 5's range", x))
print("ok: active T_c/T_a inside the paper's window (1, 1.2)")
