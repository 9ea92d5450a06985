-- Invasion into tethered adipose tissue (docs/model.md, protocol steps 1-5, 7): the main job's
-- chain with ECM springs between neighbouring adipocytes (stiffness K_ecm, a mean of 6 per
-- adipocyte) inserted right after compression, so that their rest lengths are the
-- separations of the compressed tissue (the paper's "initial configuration"), their
-- heterogeneity lambda, then the quench, a further equilibration and production.
--   invasim run protocols/tethered.lua --set K_ecm=0.04 --set lambda=0.3
local iv = require("invasim")
local parameters = require("lib.parameters")
local stage = require("lib.stages")
local motion = require("lib.motion")

-- Parameters: the shared ones (lib/parameters.lua) and this protocol's own.
local p = iv.params(parameters.merge{
  K_ecm = { 0.04, range = "[0, inf)", unit = "eps_c/sigma^2", help = "ECM tether stiffness" },
  mean_degree = { 6.0, range = "(0, inf)", help = "mean number of tethers per adipocyte" },
  lambda = { 0.0, range = "[0, 1]", help = "tether heterogeneity: rest lengths (1 -+ lambda) R_ij in the lower/upper half in z" },
  equilibrate_steps = { 10000, type = "integer", range = "[0, inf)", help = "steps after the quench before production" },
})
parameters.validate(p)
local N_a, N_c, L0 = parameters.size(p)
local clock = iv.clock()

local out = require("lib.run_dir").open(p)

-- Initial configuration and compression, as in invasion.lua.
local tissue = stage.init(parameters.init_options(p, N_a, N_c, L0))
stage.compress(tissue, { to_phi = p.phi, ftol = p.compress_ftol, final_ftol = p.final_ftol,
                         cohesion = p.cohesive_compression, out = out, from = iv.from })

-- ECM tethers between neighbouring adipocytes, rest lengths = the compressed separations;
-- then their heterogeneity: rest lengths (1 - lambda) R_ij in the lower half in z,
-- (1 + lambda) R_ij in the upper half (lambda = 0 leaves them as they are).
stage.tether(tissue, { K = p.K_ecm, mean_degree = p.mean_degree })
stage.heterogeneity(tissue, { lambda = p.lambda })

-- Quench (piston at P, the cells' motion), then a further equilibration with the same motion.
stage.quench(tissue, motion.quench_options(p, { steps = p.quench_steps }))
stage.quench(tissue, motion.quench_options(p, { label = "equilibrate", steps = p.equilibrate_steps }))

-- Production and report, as in invasion.lua.
local result = stage.production(tissue, parameters.production_options(p, out))
require("lib.report").final(tissue, p, result, iv.clock() - clock, out)
