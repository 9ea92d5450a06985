-- Test protocol (resume_after_kill.sh with PROTOCOL=contacts_midrun.lua): the main job's stages
-- with the cells' cohesion raised from beta to beta_after at the first sample at or after
-- production step change_step, as a user's protocol may change a parameter while it runs. A
-- run stopped after that change and resumed continues with the changed contacts (the
-- checkpoint holds them), so it ends as the run never stopped.
package.path = "../../protocols/?.lua;" .. package.path  -- the stage library (run from tests/lua)
local iv = require("invasim")
local parameters = require("lib.parameters")
local stage = require("lib.stages")
local motion = require("lib.motion")

local declarations = parameters.declarations()
declarations.change_step = { 300, range = "[0, inf)", unit = "steps", help = "production step of the change" }
declarations.beta_after = { 0.05, range = "[0, inf)", help = "the cells' cohesion after the change" }
local p = iv.params(declarations)
parameters.validate(p)
local N_a, N_c, L0 = parameters.size(p)
local out = require("lib.run_dir").open(p)
local tissue = stage.init(parameters.init_options(p, N_a, N_c, L0))
stage.compress(tissue, { to_phi = p.phi, ftol = p.compress_ftol, final_ftol = p.final_ftol,
                         cohesion = p.cohesive_compression, out = out, from = iv.from })
stage.quench(tissue, motion.quench_options(p, { steps = p.quench_steps }))
local start = tissue.sys:step()
local options = parameters.production_options(p, out)
options.on_sample = function(_, t)
  if t.sys:step() - start >= p.change_step and t.contacts:params().beta ~= p.beta_after then
    t.contacts:set{ beta = p.beta_after }
  end
end
local result = stage.production(tissue, options)
require("lib.report").final(tissue, p, result, 0, out)
