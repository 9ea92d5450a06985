-- One point of the adipocyte packing-fraction scan (docs/model.md, protocol step 6, the paper's
-- Fig. "variance"): compress, rescale the box affinely to the adipocyte packing fraction
-- phi_a and minimise, tether the adipocytes (K_ecm = 0.04, lambda; rest lengths from the
-- rescaled, minimised tissue), then run under the pressure wall at P as the paper does (its
-- whole scan is at one k_B T/(P sigma^3) = 0.37) and measure. The pressure wall lets the
-- tissue move away from the target phi_a: the run reports the measured phi_a (mean over
-- production and final value) beside the target, and says so in the log when it drifts by
-- more than 0.05 (lib/packing_drift.lua; docs/model.md gives the numbers).
--   invasim run protocols/packing.lua --set phi_a=0.6
local iv = require("invasim")
local protocol = require("lib.protocol")

local p = iv.params(protocol.merge{
  phi_a = { 0.6, range = "(0, 1)", help = "adipocyte packing fraction of this scan point (0.4-0.9)" },
  K_ecm = { 0.04, range = "[0, inf)", unit = "eps_c/sigma^2", help = "ECM tether stiffness (0: no tethers)" },
  lambda = { 0.0, range = "[0, 1]", help = "tether heterogeneity" },
  f0 = { 0.012, range = "[0, inf)", unit = "eps_c/sigma", help = "self-propulsion force (0.012: k_B T_c/(P sigma^3) ~ 0.37 in the paper's convention, docs/model.md)" },
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
protocol.quench(tissue, p)
local result = protocol.produce(tissue, p, out)
local packing = require("lib.packing_drift")(p.phi_a, result, { P = p.P })
require("lib.report").final(tissue, p, result, iv.clock() - clock, out, { packing_scan = packing })
