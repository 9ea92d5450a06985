-- Invasion into tethered adipose tissue (docs/model.md, protocol steps 1-5, 7): the main job's chain
-- with ECM springs between neighbouring adipocytes (stiffness K_ecm, a mean of 6 per
-- adipocyte) inserted right after compression, so that their rest lengths are the
-- separations of the compressed tissue (the paper's "initial configuration"), their
-- heterogeneity lambda, then the quench, a further equilibration and production.
--   invasim run protocols/tethered.lua --set K_ecm=0.04 --set lambda=0.3
local iv = require("invasim")
local protocol = require("lib.protocol")

local p = iv.params(protocol.merge{
  K_ecm = { 0.04, range = "[0, inf)", unit = "eps_c/sigma^2", help = "ECM tether stiffness" },
  mean_degree = { 6.0, range = "(0, inf)", help = "mean number of tethers per adipocyte" },
  lambda = { 0.0, range = "[0, 1]", help = "tether heterogeneity: rest lengths (1 -+ lambda) R_ij in the lower/upper half in z" },
  equilibrate_steps = { 10000, type = "integer", range = "[0, inf)", help = "steps after the quench before production" },
})

protocol.validate(p)
local clock = iv.clock()
local out = require("lib.run_dir").open(p)
local tissue = protocol.compressed(p, out)
require("lib.tether")(tissue, { K = p.K_ecm, mean_degree = p.mean_degree })
if p.lambda > 0 then require("lib.heterogeneity")(tissue, { lambda = p.lambda }) end
protocol.quench(tissue, p)
require("lib.quench")(tissue, { label = "equilibrate", P = p.P, kT = p.kT, f0 = p.f0,
                                tau_p = p.tau_p, gamma = p.gamma, vertex_bath = p.vertex_bath,
                                vertex_gamma = p.vertex_gamma, dt = p.dt,
                                steps = p.equilibrate_steps })
local result = protocol.produce(tissue, p, out)
require("lib.report").final(tissue, p, result, iv.clock() - clock, out)
