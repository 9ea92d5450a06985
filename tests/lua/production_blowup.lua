-- Test: a production run that blows up (here: a time step far beyond stability)
-- stops with the engine's diagnostic (step, site, value) and names the last good checkpoint,
-- which stays intact and loadable.
package.path = "../../protocols/?.lua;" .. package.path
local iv = require("invasim")
local p = iv.params{ seed = 1 }
local out = iv.out_dir
iv.make_dirs(out .. "/checkpoint")
local tissue = require("lib.init"){ N_a = 2, N_c = 60, L0 = 30.0, seed = p.seed }
require("lib.compress")(tissue, { to_phi = 0.5, progress = false })
require("lib.quench")(tissue, { kT = 1e-3, steps = 100, progress = false })
local production = require("lib.production")
production(tissue, { steps = 400, every = 100, checkpoint_every = 200, out = out, progress = false,
                     correlate_every = 0, slices_per_body = 0 })
local saved_step = tissue.last_checkpoint.step   -- the checkpoint of its last step (500)
tissue.dyn:set_dt(4.0)   -- unstable: contacts blow the cells apart
local ok, err = pcall(production, tissue, { steps = 100000, every = 100, checkpoint_every = 200000,
                                            out = out, progress = false, correlate_every = 0 })
assert(not ok, "the unstable run should have stopped")
print(err)
assert(err:find("blow%-up at step %d+: site %d+ %(") , "no blow-up diagnostic: " .. err)
assert(err:find("last good checkpoint: .*state%.ckpt %(step " .. saved_step .. "%)", 1, false),
       "no checkpoint named: " .. err)
-- The checkpoint is intact: it loads into a fresh copy and resumes at the saved step.
local copy = require("lib.init"){ N_a = 2, N_c = 60, L0 = 30.0, seed = p.seed }
require("lib.quench")(copy, { kT = 1e-3, steps = 0, progress = false })
iv.load_checkpoint(out .. "/checkpoint/state.ckpt", { system = copy.sys, dynamics = copy.dyn })
assert(copy.sys:step() == saved_step, "checkpoint step " .. copy.sys:step())
print("production_blowup: stopped with a diagnostic; checkpoint of step " .. saved_step .. " intact")
