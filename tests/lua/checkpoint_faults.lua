-- Used by checkpoint_faults.sh: a small production run writing a checkpoint every
-- 200 steps to <out>/checkpoint/state.ckpt (the fault hooks of io/test_hooks.hpp act on its
-- writes); with --set check=PATH it only loads that checkpoint into a fresh tissue and prints
-- its step.
package.path = "../../protocols/?.lua;" .. package.path
local iv = require("invasim")
local p = iv.params{ seed = 1, check = "" }
local function tissue_with_dynamics()
  local tissue = require("lib.init"){ N_a = 2, N_c = 60, L0 = 30.0, seed = p.seed }
  return tissue
end
if p.check ~= "" then
  local copy = tissue_with_dynamics()
  require("lib.quench")(copy, { kT = 1e-3, steps = 0, progress = false })
  iv.load_checkpoint(p.check, { system = copy.sys, dynamics = copy.dyn })
  print("checkpoint_faults: loaded " .. p.check .. " at step " .. copy.sys:step())
  return
end
local out = iv.out_dir
iv.make_dirs(out .. "/checkpoint")
local tissue = tissue_with_dynamics()
require("lib.compress")(tissue, { to_phi = 0.5, progress = false })
require("lib.quench")(tissue, { kT = 1e-3, steps = 0, progress = false })
require("lib.production")(tissue, { steps = 2000, every = 100, checkpoint_every = 200, out = out,
                                    progress = false, correlate_every = 0, slices_per_body = 0 })
print("checkpoint_faults: the run ended")
