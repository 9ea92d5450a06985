-- Stage "tether" (docs/model.md, protocol step 4): ECM springs U = K/2 (R_ij - l_ij0)^2 between
-- adipocyte centres, the closest pairs so that each adipocyte has `mean_degree` tethers on
-- average (cutoff d_c reported), rest lengths = the current separations. The protocols call
-- it right after compression (packing.lua: after the rescale), before the quench. While a
-- resume is pending the tethers are built all the same and the checkpoint replaces them.
--
--   require("lib.tether")(tissue, { K = 0.04 })
local iv = require("invasim")
local log = require("lib.log")

local spec = {
  K = { 0.04, range = "[0, inf)", unit = "eps_c/sigma^2", help = "tether stiffness" },
  mean_degree = { iv.Tethers.connect.defaults.mean_degree, type = "number", range = "(0, inf)" },
}

return function(tissue, opts)
  local o = iv.keywords("tether", opts, spec)
  if tissue.tethers then error("tether: this tissue already has tethers", 2) end
  local tethers = tissue.sys:add(iv.Tethers{ K = o.K })
  local d_c = tethers:connect{ mean_degree = o.mean_degree }
  tissue.tethers = tethers
  log.say("tether", "%d tethers (K = %g) between %d adipocytes, cutoff d_c = %.4f%s",
          tethers:count(), tethers:K(), tissue.sys:n_adipocytes(), d_c,
          require("lib.resume").pending() and " (resuming: the checkpoint's tethers replace these)" or "")
  return d_c
end
