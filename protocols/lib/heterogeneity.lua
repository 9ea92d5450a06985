-- Stage "heterogeneity" (docs/model.md, protocol step 5): tethers in the lower half of the box in z
-- (by their midpoint) get rest length (1 - lambda) R_ij, the others (1 + lambda) R_ij.
-- lambda = 0 (uniform tissue) leaves the rest lengths as the tether stage set them.
--
--   require("lib.heterogeneity")(tissue, { lambda = 0.3 })
local iv = require("invasim")
local log = require("lib.log")

local spec = { lambda = { type = "number", required = true, range = "[0, 1]", help = "rest-length contrast" } }

return function(tissue, opts)
  local o = iv.keywords("heterogeneity", opts, spec)
  if not tissue.tethers then
    error("heterogeneity: the tissue has no tethers; run the tether stage first", 2)
  end
  if o.lambda == 0 then
    log.say("heterogeneity", "lambda = 0: uniform rest lengths on %d tethers", tissue.tethers:count())
    return
  end
  tissue.tethers:heterogeneity{ lambda = o.lambda }
  -- With K = 0 the rest lengths change but no tether pulls: say so rather than imply an effect.
  log.say("heterogeneity", "lambda = %g on %d tethers%s", o.lambda, tissue.tethers:count(),
          tissue.tethers:K() == 0 and " (K = 0: the tethers exert no force, so lambda has no effect)" or "")
end
