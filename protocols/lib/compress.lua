-- Stage "compress" (docs/model.md, protocol step 2): athermal isotropic compression in steps of
-- Delta phi / phi = `step` (adipocytes move rigidly), each followed by FIRE to `ftol`, until
-- the total packing fraction reaches `to_phi`; then one last FIRE to `final_ftol`. Reports the
-- final box (the paper's L_f; docs/model.md: stop at phi, never at a hard-coded L_f).
--
-- Decisions (docs/model.md): the minimisations between steps stop at ftol = 1e-3 and only the
-- final state is minimised tightly (final_ftol = 1e-6): the intermediate states are not
-- measured, and near jamming each 3 % step costs 1e4-1e5 FIRE iterations at ftol = 1e-4.
-- Cohesion is off during compression by default (`beta = 0`: athermal packing of repulsive
-- bodies, as in the DPM literature); the contacts get back their own beta afterwards.
--
--   local report = require("lib.compress")(tissue, { to_phi = 0.72 })
local iv = require("invasim")
local options = require("lib.options")
local log = require("lib.log")

local defaults = {
  to_phi = 0.72, step = 0.03, ftol = 1e-3, final_ftol = 1e-6,
  beta = 0.0,                 -- cohesion depth during compression
  max_steps = 1000000,        -- FIRE iterations per minimisation
  progress = true,
  save = options.OPTIONAL,    -- path: save the compressed tissue there (a checkpoint)
}

local resume = require("lib.resume")

return function(tissue, opts)
  local o = options.check("compress", opts, defaults, { save = "string" })
  if resume.pending() then
    log.say("compress", "skipped: resuming from a checkpoint")
    return { skipped = true }
  end
  local sys, contacts = tissue.sys, tissue.contacts
  local beta = contacts:params().beta
  contacts:set{ beta = o.beta }
  log.say("compress", "to phi = %g in steps of %g, FIRE to %g (final %g), cohesion beta = %g during compression",
          o.to_phi, o.step, o.ftol, o.final_ftol, contacts:params().beta)
  local progress = o.progress and iv.Progress{ total = 0, label = "compress", every_seconds = 10 } or nil
  local clock = iv.clock()
  local last = 0
  local report = iv.compress(sys, {
    to_phi = o.to_phi, step = o.step, ftol = o.ftol, max_steps = o.max_steps,
    callback = function(r)
      last = r.steps
      if progress then progress:update(r.steps) end
    end,
  })
  if progress then progress:finish() end
  local final = iv.Fire{ ftol = o.final_ftol, max_steps = o.max_steps }:minimize(sys)
  contacts:set{ beta = beta }
  report.final = final
  report.max_force = final.max_force
  report.converged = final.converged
  report.seconds = iv.clock() - clock
  if o.save then  -- the compressed tissue, for runs started with --from this run's directory
    local resume = require("lib.resume")
    iv.save_checkpoint(o.save, resume.stamp{ system = sys, extra = resume.serialize{
      box = report.box, phi = report.phi, steps = report.steps } })
  end
  local box = sys:box().lengths
  log.say("compress", "phi = %.4f after %d steps (%d FIRE iterations); final box L_f = %s; max force %.2e (%s)",
          sys:packing().total, last, report.fire_steps + final.steps, log.box(box), final.max_force,
          final.converged and "converged" or "NOT converged to " .. o.final_ftol)
  return report
end
