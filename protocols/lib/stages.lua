-- The stages a protocol chains, by name (docs/protocols.md). Each stage is one file
-- lib/<name>.lua holding a function (tissue, {keywords}) whose keywords are checked like the
-- engine's constructors; `init` takes only the keywords and returns the tissue the others
-- work on. Stages know how to skip or restore their own work, so protocols read as a plain
-- chain: while a --resume from a production checkpoint is pending (lib.resume), compress and
-- rescale skip their work and quench its steps (init, tether and quench still build their
-- objects, into which production loads the checkpoint); compress continues a compression
-- stopped by a signal, and takes the compressed tissue of another run with `from`.
--
--   local stage = require("lib.stages")
--   local tissue = stage.init{ N_a = 8, N_c = 400, L0 = 46 }
--   stage.compress(tissue, { to_phi = 0.72 })
local iv = require("invasim")
local resume = require("lib.resume")

local production = require("lib.production")

local M = {
  init = require("lib.init"),                     -- dilute tissue (docs/model.md, step 1)
  compress = require("lib.compress"),             -- to phi, cohesion off (step 2)
  rescale = require("lib.rescale"),               -- affinely to phi_a, then FIRE (step 6)
  tether = require("lib.tether"),                 -- ECM springs between adipocytes (step 4)
  heterogeneity = require("lib.heterogeneity"),   -- rest lengths (1 -+ lambda) R_ij (step 5)
  quench = require("lib.quench"),                 -- pressure wall at P, cells' motion (step 3)
}

-- Stage "production" (step 7, lib/production.lua) with snapshots in the run directory:
-- `snapshot_every` (steps, 0: none) writes out/snapshots/ at the start and at the steps that
-- are multiples of it, on its own schedule (it need not be a multiple of `every`). The other
-- keywords are lib/production.lua's.
function M.production(tissue, opts)
  opts = opts or {}
  -- An integer, or a float with an integral value (1e3), as iv.keywords takes integers.
  local every = opts.snapshot_every or 0
  every = type(every) == "number" and math.tointeger(every) or every
  if math.type(every) ~= "integer" or every < 0 then
    error("production: key 'snapshot_every' must be an integer >= 0, got " .. tostring(every), 2)
  end
  local own = {}
  for k, v in pairs(opts) do own[k] = v end
  own.snapshot_every = every
  -- Without a run directory there is nowhere to write them: refused, not dropped.
  for _, key in ipairs({ "snapshot_every", "checkpoint_every" }) do
    local n = own[key]
    if type(n) == "number" and n > 0 and not opts.out then
      error(string.format("production: %s = %s needs out (a run directory) to write into",
                          key, tostring(n)), 2)
    end
  end
  if every > 0 and opts.out then
    -- With proliferation, each cell's identity (deaths shift the cells' order).
    own.snapshots = iv.Snapshots{ dir = opts.out .. "/snapshots", ids = opts.proliferation ~= nil }
    if not resume.pending() then own.snapshots:write(tissue.sys) end
  else
    own.snapshot_every = nil
  end
  return production(tissue, own)
end

return M
