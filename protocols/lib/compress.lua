-- Stage "compress" (docs/model.md, protocol step 2): athermal isotropic compression in steps of
-- Delta phi / phi = `step` (adipocytes move rigidly), each followed by FIRE to `ftol`, until
-- the total packing fraction reaches `to_phi`; then one last FIRE to `final_ftol`. Sets and
-- returns tissue.compression, the report with the box it reached (the paper's L_f): the
-- target is phi, not the paper's stated L_f = 34, which its own numbers contradict
-- (docs/model.md).
--
-- Cohesion (and the optional cell-adipocyte adhesion) is off during compression unless
-- `cohesion = true` (athermal packing of repulsive bodies, as in the DPM literature): the
-- stage hands `contacts = {beta = 0, beta_cv = 0}` to the engine's compression and final
-- FIRE, which apply it for their own duration only and give the contacts their own values
-- back on every exit (return, stop signal, error).
--
-- In a run directory (`out`), the compressed tissue is saved to out/checkpoint/compressed.ckpt
-- for runs started with --from this run. A stop signal (SIGINT/SIGTERM) stops the compression
-- at the next FIRE iteration; the partly compressed tissue (velocities included), the counters
-- so far and the minimiser's own state (dt, alpha, its counters) are saved to
-- out/checkpoint/compressing.ckpt, and a --resume run continues from it to the same
-- compressed tissue, bit for bit; likewise inside the final FIRE (its state saved with the
-- report of the compression steps).
--
-- The stage knows when not to compress: with `from` (a run directory, e.g. invasim.from), the
-- compressed tissue that run saved replaces the compression (same system size, this run's
-- seed); a --resume of a run stopped after its compression loads the run's own compressed
-- tissue, report included, and continues exactly like the run that was not stopped; while a
-- --resume from a production checkpoint is pending it only logs that it is skipped (the
-- checkpoint replaces the tissue).
--
-- Decisions (docs/model.md): the minimisations between steps stop at ftol = 1e-3 and only the
-- final state is minimised tightly (final_ftol = 1e-6): the intermediate states are not
-- measured, and near jamming each 3 % step costs 1e4-1e5 FIRE iterations at ftol = 1e-4.
-- FIRE's largest time step `dt_max` defaults to 0.15 sqrt(1e3 / eps_v) (at most 0.15) when
-- the tissue has adipocytes, below the stability limit of their volume mode (see
-- lib.fire_step); without adipocytes, the engine's default.
--
--   require("lib.compress")(tissue, { to_phi = 0.72, out = out, from = invasim.from })
local iv = require("invasim")
local log = require("lib.log")

-- step and max_steps default to the engine's (invasim.compress.defaults, invasim.Fire.defaults).
local spec = {
  to_phi = 0.72, step = iv.compress.defaults.step, ftol = 1e-3, final_ftol = 1e-6,
  cohesion = false,           -- keep the cancer cells' cohesion (beta) and adhesion (beta_cv) on while compressing
  max_steps = iv.Fire.defaults.max_steps,  -- FIRE iterations per minimisation
  dt_max = { type = "number", range = "(0, inf)" },  -- FIRE's largest time step (default: lib.fire_step)
  progress = true,
  out = { type = "string" },         -- the run directory: compressed.ckpt (for --from) and, on
                              -- SIGINT/SIGTERM, compressing.ckpt (for --resume)
  from = { type = "string" },        -- a run directory whose compressed tissue replaces the compression
}

local resume = require("lib.resume")
local fire_step = require("lib.fire_step")

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
  error(string.format("stopped by %s %s (phi = %.4f); checkpoint saved to %s; continue with: %s",
                      signal, where, phi, o.checkpoint, resume.continue_command()), 0)
end

-- A compression step whose FIRE reached its iteration limit without reaching ftol: the
-- minimisation stalled (a tolerance below what the forces' rounding allows, or a tissue that
-- cannot relax), and every further step would run to the limit too. Stops the run saying so.
local function stalled(r, o)
  error(string.format("compress: the FIRE of compression step %d stopped at its iteration limit " ..
                      "(max_steps = %d) with max force %.3g, above ftol = %g (phi = %.4f): the " ..
                      "minimisation stalled; raise ftol (the protocols' compress_ftol) or max_steps",
                      r.steps, o.max_steps, r.max_force, o.ftol, r.phi), 0)
end

-- The compressed tissue that the run in directory `from` saved, loaded into tissue.sys, and
-- that compression's report (the whole report, of which --from needs box, phi and steps).
local function load_compressed(tissue, from)
  local path = resume.compressed_path(from)
  local saved = resume.deserialize(iv.load_checkpoint(path, { system = tissue.sys, seed = tissue.params.seed }), path)
  saved.from = path
  log.say("compress", "skipped: the compressed tissue of %s (box %.4g, phi = %.4f)", from, saved.box[1], saved.phi)
  return saved
end

-- This run's own compressed tissue and report, when a --resume continues a run that was
-- stopped after its compression (lib.resume.compressed_pending).
local function load_own_compressed(tissue, out)
  local path = resume.compressed_path(out)
  local report = resume.deserialize(iv.load_checkpoint(path, { system = tissue.sys }), path)
  resume.compressed_done()
  log.say("compress", "skipped: resumed from this run's compressed tissue %s (box %.4g, phi = %.4f)",
          path, report.box[1], report.phi)
  return report
end

-- Compresses (or continues a compression stopped by a signal); returns the report.
local function compress(tissue, o)
  local sys = tissue.sys
  -- The checkpoint directory before the work, not a failed save after it (an `out` that is
  -- no run directory yet, or cannot be written, is refused here, naming it).
  if o.out then iv.make_dirs(o.out .. "/checkpoint") end
  local save = o.out and resume.compressed_path(o.out) or nil
  o.checkpoint = o.out and resume.compressing_path(o.out) or nil
  -- Cohesion and adhesion off: the engine applies this for the compression and the final FIRE
  -- only.
  local during = (not o.cohesion and tissue.contacts) and { contacts = { beta = 0.0, beta_cv = 0.0 } } or nil
  local now = tissue.contacts and tissue.contacts:params() or { beta = 0.0, beta_cv = 0.0 }
  local beta, beta_cv = during and 0.0 or now.beta, during and 0.0 or now.beta_cv
  local dt_max = o.dt_max or fire_step.dt_max(tissue)
  log.say("compress", "to phi = %g in steps of %g, FIRE to %g (final %g, dt_max %g), cohesion beta = %g%s during compression",
          o.to_phi, o.step, o.ftol, o.final_ftol, dt_max, beta,
          beta_cv > 0 and string.format(", adhesion beta_cv = %g", beta_cv) or "")
  local saved  -- the state of a compression stopped by a signal, when resuming it
  if o.checkpoint and resume.compression_pending() then
    saved = resume.deserialize(iv.load_checkpoint(o.checkpoint, { system = sys }), o.checkpoint)
    resume.compression_done()
    local where = saved.final_fire and string.format(" and %d iterations of the final FIRE", saved.final_fire.steps)
                  or (saved.report and " and the final FIRE" or "")
    log.say("compress", "resumed after %d compression steps%s (phi = %.4f) from %s",
            (saved.report or saved.compress).steps, where, sys:packing().total, o.checkpoint)
  end
  local clock = iv.clock()
  -- A compression stopped after its steps: in (saved.final_fire) or after its final FIRE.
  local report = saved and saved.report
  if not report then
    local progress = o.progress and iv.Progress{ total = 0, label = "compress", every_seconds = 10 } or nil
    report = iv.compress(sys, {
      to_phi = o.to_phi, step = o.step, ftol = o.ftol, max_steps = o.max_steps, dt_max = dt_max,
      continue_from = saved and saved.compress, contacts = during and during.contacts,
      callback = function(r)  -- each step in log.txt (the course of the compression)
        log.note("compress", "step %d: phi = %.4f, %d FIRE iterations so far", r.steps, r.phi, r.fire_steps)
        if progress then progress:update(r.steps) end
        if not r.converged then stalled(r, o) end
      end,
    })
    if progress then
      if report.stopped then progress:stop() else progress:finish() end
    end
    if report.stopped then
      local inside = report.fire_state and string.format(", inside the FIRE of step %d at iteration %d",
                                                          report.steps + 1, report.fire_state.steps) or ""
      stop(sys, o, { compress = { steps = report.steps, fire_steps = report.fire_steps,
                                  converged = report.converged, max_force = report.max_force,
                                  fire_state = report.fire_state } },
           string.format("during compression after step %d%s", report.steps, inside))
    end
    report.stopped = nil
  end
  if not report.final then
    -- The final FIRE (or the rest of one stopped by a signal): a signal stops it before its
    -- next iteration, and the tissue, the report and the minimiser's state are saved.
    local final = iv.Fire{ ftol = o.final_ftol, max_steps = o.max_steps, dt_max = dt_max }:minimize(sys, {
      contacts = during and during.contacts, stop_on_signal = true,
      continue_from = saved and saved.final_fire and { fire_state = saved.final_fire } })
    if final.stopped then
      stop(sys, o, { report = report, final_fire = final.fire_state },
           string.format("after compression step %d, inside the final FIRE at iteration %d",
                         report.steps, final.fire_state.steps))
    end
    report.final = final
    report.max_force = final.max_force
    report.converged = final.converged
    if not final.converged then
      log.say("compress", "WARNING: the final FIRE stopped at its iteration limit (max_steps = %d) " ..
              "with max force %.3g, above final_ftol = %g: the compressed tissue is not minimised",
              o.max_steps, final.max_force, o.final_ftol)
    end
    -- A signal after the final FIRE: the compressed tissue and this report are saved.
    if iv.interrupted() then stop(sys, o, { report = report }, "after the compression") end
  end
  -- (No wall-clock time in the report: it goes into the production checkpoint, which must be
  -- the same bytes for the same run; the log line says how long this took.)
  local seconds = iv.clock() - clock
  if save then  -- the compressed tissue and its report, for --from and --resume
    iv.save_checkpoint(save, resume.stamp{ system = sys, extra = resume.serialize(report) })
  end
  if o.checkpoint and iv.exists(o.checkpoint) then iv.remove_path(o.checkpoint) end
  local box = sys:box().lengths
  log.say("compress", "phi = %.4f after %d steps (%d FIRE iterations); final box L_f = %s; max force %.2e (%s); %.1f s",
          sys:packing().total, report.steps, report.fire_steps + report.final.steps, log.box(box),
          report.max_force, report.converged and "converged" or "NOT converged to " .. o.final_ftol,
          seconds)
  return report
end

return function(tissue, opts)
  local o = iv.keywords("compress", opts, spec)
  if resume.pending() then
    log.say("compress", "skipped: resuming from a checkpoint")
    tissue.compression = { skipped = true }
  elseif o.out and resume.compressed_pending() then
    tissue.compression = load_own_compressed(tissue, o.out)
  elseif o.from then
    tissue.compression = load_compressed(tissue, o.from)
  else
    tissue.compression = compress(tissue, o)
  end
  return tissue.compression
end
