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
  -- The default mean degree asks for more tethers than a tissue of few adipocytes has pairs:
  -- there it tethers all of them (a mean degree given is the engine's to refuse).
  local n_a, all_pairs = tissue.sys:n_adipocytes(), ""
  if not (opts and opts.mean_degree) and o.mean_degree > n_a - 1 and n_a >= 2 then
    o.mean_degree = n_a - 1
    all_pairs = string.format(" (all pairs: the default mean degree %g needs %g adipocytes)",
                              spec.mean_degree[1], spec.mean_degree[1] + 1)
  end
  local tethers = tissue.sys:add(iv.Tethers{ K = o.K })
  local d_c = tethers:connect{ mean_degree = o.mean_degree }
  tissue.tethers = tethers
  log.say("tether", "%d tethers (K = %g) between %d adipocytes, cutoff d_c = %.4f%s%s",
          tethers:count(), tethers:K(), n_a, d_c, all_pairs,
          require("lib.resume").pending() and " (resuming: the checkpoint's tethers replace these)" or "")
  return d_c
end
