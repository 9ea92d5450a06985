-- Stage "compress" (docs/model.md, protocol step 2): athermal isotropic compression in steps of
-- Delta phi / phi = `step` (adipocytes move rigidly), each followed by FIRE to `ftol`, until
-- the total packing fraction reaches `to_phi`; then one last FIRE to `final_ftol`. Reports the
-- box it reached (the paper's L_f): the target is phi, not the paper's stated L_f = 34, which
-- its own numbers contradict (docs/model.md).
--
-- A stop signal (SIGINT/SIGTERM) stops the compression at the next compression-step boundary
-- (after the FIRE of the current step has converged); with `checkpoint`, the partly
-- compressed tissue and the counters so far are saved there, and a --resume run continues
-- from it to the same compressed tissue, bit for bit (each step starts from a converged state
-- at rest, so nothing of the minimiser's own state is needed). The final FIRE is not
-- interrupted: a signal during it stops the run after it, with the compressed tissue saved.
--
-- Decisions (docs/model.md): the minimisations between steps stop at ftol = 1e-3 and only the
-- final state is minimised tightly (final_ftol = 1e-6): the intermediate states are not
-- measured, and near jamming each 3 % step costs 1e4-1e5 FIRE iterations at ftol = 1e-4.
-- Cohesion is off during compression by default (`beta = 0`: athermal packing of repulsive
-- bodies, as in the DPM literature); the contacts get back their own beta afterwards.
--
--   local report = require("lib.compress")(tissue, { to_phi = 0.72 })
local iv = require("invasim")
local log = require("lib.log")

-- step, beta and max_steps default to the engine's (invasim.compress.defaults, the
-- Contacts' beta = 0: no cohesion, invasim.Fire.defaults).
local spec = {
  to_phi = 0.72, step = iv.compress.defaults.step, ftol = 1e-3, final_ftol = 1e-6,
  beta = iv.Contacts.defaults.beta,  -- cohesion depth during compression
  max_steps = iv.Fire.defaults.max_steps,  -- FIRE iterations per minimisation
  progress = true,
  save = { "string" },        -- path: save the compressed tissue there (a checkpoint)
  checkpoint = { "string" },  -- path: on SIGINT/SIGTERM, save the partly compressed
                              -- tissue there (--resume continues from it)
}

local resume = require("lib.resume")

-- Saves the (partly) compressed tissue and `state` to o.checkpoint on a stop signal and stops
-- the run with a message saying how to continue it.
local function stop(sys, o, state, where)
  local signal = iv.interrupted() or "a signal"
  local phi = sys:packing().total
  if not o.checkpoint then
    error(string.format("stopped by %s %s (phi = %.4f); no run directory, nothing saved", signal,
                        where, phi), 0)
  end
  iv.save_checkpoint(o.checkpoint, resume.stamp{ system = sys, extra = resume.serialize(state) })
  log.note("compress", "checkpoint %s written to %s", where, o.checkpoint)
  error(string.format("stopped by %s %s (phi = %.4f); checkpoint saved to %s; continue with: " ..
                      "invasim run --resume %s", signal, where, phi, o.checkpoint,
                      resume.run_dir() or "DIR"), 0)
end

return function(tissue, opts)
  local o = iv.keywords("compress", opts, spec)
  if resume.pending() then
    log.say("compress", "skipped: resuming from a checkpoint")
    return { skipped = true }
  end
  local sys, contacts = tissue.sys, tissue.contacts
  local beta = contacts:params().beta
  contacts:set{ beta = o.beta }
  log.say("compress", "to phi = %g in steps of %g, FIRE to %g (final %g), cohesion beta = %g during compression",
          o.to_phi, o.step, o.ftol, o.final_ftol, contacts:params().beta)
  local saved  -- the state of a compression stopped by a signal, when resuming it
  if o.checkpoint and resume.compression_pending() then
    saved = resume.deserialize(iv.load_checkpoint(o.checkpoint, { system = sys }))
    resume.compression_done()
    log.say("compress", "resumed after %d compression steps%s (phi = %.4f) from %s",
            (saved.report or saved.compress).steps, saved.report and " and the final FIRE" or "",
            sys:packing().total, o.checkpoint)
  end
  local clock = iv.clock()
  local report = saved and saved.report  -- a complete compression (stopped after it)
  if not report then
    local progress = o.progress and iv.Progress{ total = 0, label = "compress", every_seconds = 10 } or nil
    report = iv.compress(sys, {
      to_phi = o.to_phi, step = o.step, ftol = o.ftol, max_steps = o.max_steps,
      continue_from = saved and saved.compress,
      callback = function(r)  -- each step in log.txt (the course of the compression)
        log.note("compress", "step %d: phi = %.4f, %d FIRE iterations so far", r.steps, r.phi, r.fire_steps)
        if progress then progress:update(r.steps) end
      end,
    })
    if progress then progress:finish() end
    if report.stopped then
      stop(sys, o, { compress = { steps = report.steps, fire_steps = report.fire_steps,
                                  converged = report.converged, max_force = report.max_force } },
           string.format("during compression after step %d", report.steps))
    end
    report.stopped = nil
    local final = iv.Fire{ ftol = o.final_ftol, max_steps = o.max_steps }:minimize(sys)
    report.final = final
    report.max_force = final.max_force
    report.converged = final.converged
    -- A signal during the final FIRE: the compressed tissue and this report are saved.
    if iv.interrupted() then stop(sys, o, { report = report }, "after the compression") end
  end
  contacts:set{ beta = beta }
  -- (No wall-clock time in the report: it goes into the production checkpoint, which must be
  -- the same bytes for the same run; the log line says how long this took.)
  local seconds = iv.clock() - clock
  if o.save then  -- the compressed tissue, for runs started with --from this run's directory
    iv.save_checkpoint(o.save, resume.stamp{ system = sys, extra = resume.serialize{
      box = report.box, phi = report.phi, steps = report.steps } })
  end
  if o.checkpoint and iv.exists(o.checkpoint) then iv.remove_path(o.checkpoint) end
  local box = sys:box().lengths
  log.say("compress", "phi = %.4f after %d steps (%d FIRE iterations); final box L_f = %s; max force %.2e (%s); %.1f s",
          sys:packing().total, report.steps, report.fire_steps + report.final.steps, log.box(box),
          report.max_force, report.converged and "converged" or "NOT converged to " .. o.final_ftol,
          seconds)
  return report
end
