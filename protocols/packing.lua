-- One point of the adipocyte packing-fraction scan (docs/model.md, protocol step 6, the paper's
-- Fig. "variance"): compress, rescale the box affinely to the adipocyte packing fraction
-- phi_a and minimise, tether the adipocytes (K_ecm = 0.04, lambda; rest lengths from the
-- rescaled, minimised tissue), then run under the pressure wall at P as the paper does (its
-- whole scan is at one k_B T/(P sigma^3) = 0.37) and measure. The pressure wall lets the
-- tissue move away from the target phi_a: the run reports the measured phi_a (mean over
-- production and final value) beside the target, and says so in the log when it drifts by
-- more than 0.05 (lib/packing_drift.lua; docs/model.md gives the numbers).
-- box = "fixed" keeps both walls where the rescale put them instead (the paper's text, "by
-- changing the length of the simulation box", read literally): phi_a then stays at the
-- target and the wall pressure is measured, not set (docs/model.md, "Packing-fraction scan").
--   invasim run protocols/packing.lua --set phi_a=0.6
--   invasim run protocols/packing.lua --set phi_a=0.85 --set box=fixed
local iv = require("invasim")
local declare = require("lib.declare")
local parameters = require("lib.parameters")
local stage = require("lib.stages")
local motion = require("lib.motion")

-- Parameters: the shared ones (lib/parameters.lua) and this protocol's own.
local p = iv.params(parameters.merge{
  phi_a = { 0.6, range = "(0, 1)", help = "adipocyte packing fraction of this scan point (0.4-0.9)" },
  K_ecm = { 0.04, range = "[0, inf)", unit = "eps_c/sigma^2", help = "ECM tether stiffness (0: no tethers)" },
  lambda = { 0.0, range = "[0, 1]", help = "tether heterogeneity" },
  box = { "pressure", choices = { "pressure", "fixed" }, help = "after the rescale: pressure (the left wall a piston at P, docs/model.md protocol step 6) or fixed (both walls stay: the box keeps the rescaled size)" },
  f0 = declare.engine("Active", "f0", 0.0024, "0.0024 with the default background: 2 k_B T_c/(P sigma^3) = 0.37-0.39 over phi_a = 0.45-0.85, the paper's Fig. 8 value, docs/model.md"),
})
parameters.validate(p)
local N_a, N_c, L0 = parameters.size(p)
local clock = iv.clock()

local out = require("lib.run_dir").open(p)

-- Initial configuration and compression to phi, as in invasion.lua.
local tissue = stage.init(parameters.init_options(p, N_a, N_c, L0))
stage.compress(tissue, { to_phi = p.phi, ftol = p.compress_ftol, final_ftol = p.final_ftol,
                         cohesion = p.cohesive_compression, out = out, from = iv.from })

-- The box and all positions scaled affinely to the adipocyte packing fraction phi_a, then FIRE.
stage.rescale(tissue, { phi_a = p.phi_a, ftol = p.final_ftol })

-- ECM tethers (rest lengths from the rescaled tissue) and their heterogeneity; K_ecm = 0: none.
if p.K_ecm > 0 then
  stage.tether(tissue, { K = p.K_ecm })
  stage.heterogeneity(tissue, { lambda = p.lambda })
end

-- Quench, production and report, as in invasion.lua; then the measured phi_a beside the target.
stage.quench(tissue, motion.quench_options(p, { steps = p.quench_steps,
                                                barostat = p.box == "pressure" }))
local result = stage.production(tissue, parameters.production_options(p, out))
local packing = require("lib.packing_drift")(p.phi_a, result,
                                             { P = p.box == "pressure" and p.P or nil })
packing.box = p.box
require("lib.report").final(tissue, p, result, iv.clock() - clock, out, { packing_scan = packing })
