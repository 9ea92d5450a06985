-- Stage "rescale" (docs/model.md, protocol step 6): affine change of the box and of all positions
-- (adipocytes rigidly) to the adipocyte packing fraction phi_a, then FIRE. With a Dynamics
-- that has a pressure wall, the wall is minimised too (mechanical equilibrium at its P);
-- `with_wall = false` keeps the walls fixed. FIRE's largest step is the compression's
-- (lib.fire_step: below the stability limit of the adipocytes' volume mode).
--
--   require("lib.rescale")(tissue, { phi_a = 0.6 })
local iv = require("invasim")
local log = require("lib.log")
local fire_step = require("lib.fire_step")

local spec = {
  phi_a = { type = "number", required = true, range = "[0, 1]", help = "adipocyte packing fraction to reach" },
  ftol = { 1e-6, range = "(0, inf)", help = "FIRE tolerance after the rescale" },
  max_steps = { iv.rescale.defaults.max_steps, type = "integer", range = "[0, inf)" },
  dt_max = { type = "number", range = "(0, inf)", help = "FIRE's largest time step (default: lib.fire_step's)" },
}

return function(tissue, opts)
  local o = iv.keywords("rescale", opts, spec)
  if require("lib.resume").pending() then
    log.say("rescale", "skipped: resuming from a checkpoint")
    return { skipped = true }
  end
  local sys = tissue.sys
  local before = sys:packing()
  local dt_max = o.dt_max or fire_step.dt_max(tissue)
  local r = iv.rescale(sys, { phi_a = o.phi_a, ftol = o.ftol, max_steps = o.max_steps,
                              dt_max = dt_max, stop_on_signal = true })
  local after = sys:packing()
  if r.stopped then
    -- No checkpoint inside the rescale: the compressed tissue (compressed.ckpt) is the last
    -- state saved, and --resume starts the run again from it (like a quench).
    error(string.format("stopped by %s during the rescale's FIRE at iteration %d (phi_a %.4f); " ..
                        "no checkpoint is written during the rescale: %s", iv.interrupted() or "a signal",
                        r.steps, after.adipocyte, require("lib.resume").restart_advice()), 0)
  end
  log.say("rescale", "phi_a %.4f -> %.4f (phi %.4f), box %s, FIRE %d steps (dt_max %g), max force %.2e%s",
          before.adipocyte, after.adipocyte, after.total, log.box(sys:box().lengths), r.steps,
          dt_max, r.max_force, r.converged and "" or " (NOT converged)")
  return r
end
