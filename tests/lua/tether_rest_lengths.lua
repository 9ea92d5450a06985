-- Check run by tethers_at_compression.sh on a tethered.lua run directory:
-- the tethers saved in its checkpoint (state.ckpt, during production) have rest lengths equal
-- to (1 -+ lambda) x the adipocyte separations of the compressed tissue the run started from
-- (`compressed`, a compressed.ckpt), i.e. they were inserted right after compression, before
-- the quench; and the tissue has moved since (the saved separations differ), so the check
-- can fail.
package.path = "../../protocols/?.lua;" .. package.path
local iv = require("invasim")
local p = iv.params{ run = "", compressed = "", N_a = 8, N_c = 60, L0 = 40.0, seed = 1, lambda = 0.0 }

local tissue = require("lib.init"){ N_a = p.N_a, N_c = p.N_c, L0 = p.L0, seed = p.seed }
local tethers = tissue.sys:add(iv.Tethers{ K = 0.04 })
iv.load_checkpoint(p.run .. "/checkpoint/state.ckpt", { system = tissue.sys, tethers = tethers })
local final = tethers:list()
iv.load_checkpoint(p.compressed, { system = tissue.sys })
local compressed = tethers:list()

local function check(ok, fmt, ...)
  local msg = string.format(fmt, ...)
  if not ok then error("FAILED: " .. msg, 2) end
  print("ok: " .. msg)
end

check(#compressed == 3 * p.N_a, "%d tethers (mean degree 6)", #compressed)
-- Without heterogeneity l0 = R; with it l0 = (1 -+ lambda) R.
local worst, moved = 0.0, 0.0
for k, t in ipairs(compressed) do
  local ratio = t.rest_length / t.length
  local err = math.min(math.abs(ratio - (1 - p.lambda)), math.abs(ratio - (1 + p.lambda)))
  worst = math.max(worst, err)
  moved = math.max(moved, math.abs(final[k].length - t.length))
end
check(worst < 1e-12, "rest lengths = (1 -+ %g) x the compressed separations (worst relative deviation %.2e)",
      p.lambda, worst)
check(moved > 1e-3, "the separations changed after compression (by up to %.4f), so the check discriminates", moved)
print("tether_rest_lengths: rest lengths from the compressed tissue")
