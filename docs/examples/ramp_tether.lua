-- A pressure ramp, then ECM tethers, then production (docs/protocols.md, "A worked example").
-- The tissue is compressed as in invasion.lua, the piston's pressure then rises linearly
-- from P_start to P while the cells move, the adipocytes are tethered in the tissue the ramp
-- left (rest lengths = its separations), and after an equilibration at P the run measures.
--   invasim run docs/examples/ramp_tether.lua --set P_start=2e-4 --set ramp_steps=20000
local iv = require("invasim")
local parameters = require("lib.parameters")
local stage = require("lib.stages")
local motion = require("lib.motion")

-- Parameters: the shared ones and this protocol's own, each with its range.
local p = iv.params(parameters.merge{
  P_start = { 1e-4, range = "[0, inf)", unit = "eps_c/sigma^3", help = "piston pressure at the start of the ramp (it ends at P)" },
  ramp_steps = { 20000, type = "integer", range = "[1, inf)", help = "steps of the pressure ramp" },
  K_ecm = { 0.04, range = "(0, inf)", unit = "eps_c/sigma^2", help = "ECM tether stiffness" },
})
parameters.validate(p)
local N_a, N_c, L0 = parameters.size(p)
local clock = iv.clock()

local out = require("lib.run_dir").open(p)

-- Initial configuration and compression to phi, as in invasion.lua.
local tissue = stage.init{ N_a = N_a, N_c = N_c, L0 = L0, seed = p.seed, start = p.start,
                           shape_param = p.A_0, eps_v = p.eps_v, eps_a = p.eps_a,
                           alpha = p.alpha, beta = p.beta }
stage.compress(tissue, { to_phi = p.phi, ftol = p.compress_ftol, final_ftol = p.final_ftol,
                         cohesion = p.cohesive_compression, out = out, from = iv.from })

-- The pressure ramp: a quench whose piston pressure rises linearly from P_start to P.
-- (motion.quench_options: the cells' motion and background, the vertices' bath, dt from p.)
stage.quench(tissue, motion.quench_options(p, {
  label = "ramp", P = iv.ramp{ from = p.P_start, to = p.P, steps = p.ramp_steps },
  steps = p.ramp_steps }))

-- ECM tethers between neighbouring adipocytes of the ramped tissue.
stage.tether(tissue, { K = p.K_ecm })

-- Equilibration at P, then production and the report, as in invasion.lua.
stage.quench(tissue, motion.quench_options(p, { label = "equilibrate", steps = p.quench_steps }))
local result = stage.production(tissue, { steps = p.steps, every = p.every,
                                          correlate_every = p.correlate_every,
                                          snapshot_every = p.snapshot_every,
                                          checkpoint_every = p.checkpoint_every, out = out })
require("lib.report").final(tissue, p, result, iv.clock() - clock, out)
