-- Test: a SIGTERM that arrives with the production's last steps (here sent by the observer of
-- the last sample) finishes the run: the production is complete, the summary is written and
-- the script goes on, instead of a stop that asks for a resume with nothing left to run.
package.path = "../../protocols/?.lua;" .. package.path
local iv = require("invasim")
local parameters = require("lib.parameters")
local stage = require("lib.stages")
local motion = require("lib.motion")
local p = iv.params(parameters.merge{})
local N_a, N_c, L0 = parameters.size(p)
local out = require("lib.run_dir").open(p)
local tissue = stage.init(parameters.init_options(p, N_a, N_c, L0))
stage.compress(tissue, { to_phi = p.phi, ftol = p.compress_ftol, final_ftol = p.final_ftol, out = out })
stage.quench(tissue, motion.quench_options(p, { steps = p.quench_steps }))
local last = tissue.sys:step() + p.steps
local result = stage.production(tissue, parameters.production_options(p, out, {
  on_sample = function(row)
    if row.step == last then os.execute("kill -TERM $PPID") end  -- $PPID: this invasim
  end }))
assert(tissue.sys:step() == last and #result.series.rows == p.steps // p.every, "the production ran to its end")
assert(iv.interrupted() == "SIGTERM", "the signal arrived")
require("lib.report").final(tissue, p, result, 0, out)
assert(iv.exists(out .. "/summary.json"), "summary.json written")
print("stop_at_last_step: the run finished")
