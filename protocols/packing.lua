-- One point of the adipocyte packing-fraction scan (MODEL.md protocol 6, the paper's
-- Fig. "variance"): compress, rescale the box affinely to the adipocyte packing fraction
-- phi_a and minimise, tether the adipocytes (K_ecm = 0.04, lambda), then run with both walls
-- fixed so that phi_a stays at the scan point (decision: a pressure wall would restore the
-- packing set by P), and measure.
--   invasim run protocols/packing.lua --set phi_a=0.6
local iv = require("invasim")
local protocol = require("lib.protocol")

local p = iv.params(protocol.merge{
  phi_a = { 0.6, range = "(0, 1)", help = "adipocyte packing fraction of this scan point (0.4-0.9)" },
  K_ecm = { 0.04, range = "[0, inf)", unit = "eps_c/sigma^2", help = "ECM tether stiffness (0: no tethers)" },
  lambda = { 0.0, range = "[0, 1]", help = "tether heterogeneity" },
})

protocol.validate(p)
local clock = iv.clock()
local out = require("lib.run_dir").open(p)
local tissue = protocol.compressed(p, out)
require("lib.rescale")(tissue, { phi_a = p.phi_a, ftol = p.final_ftol })
if p.K_ecm > 0 then
  require("lib.tether")(tissue, { K = p.K_ecm })
  if p.lambda > 0 then require("lib.heterogeneity")(tissue, { lambda = p.lambda }) end
end
require("lib.quench")(tissue, { barostat = false, kT = p.kT, f0 = p.f0, tau_p = p.tau_p,
                                gamma = p.gamma, vertex_bath = p.vertex_bath,
                                vertex_gamma = p.vertex_gamma, dt = p.dt, steps = p.quench_steps })
local result = protocol.produce(tissue, p, out)
require("lib.report").final(tissue, p, result, iv.clock() - clock, out)
