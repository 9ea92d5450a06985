-- Stage "quench" / "equilibrate" (MODEL.md protocol 3): the left wall becomes a piston under
-- pressure P, the cells get their thermostat or activity, the vertices are damped, and the
-- system runs for `steps` steps of dt. It creates tissue.dyn (the Dynamics every later stage
-- runs with); calling it again (equilibrate) replaces the cells' motion and the pressure and
-- keeps the piston's velocity.
--
--   require("lib.quench")(tissue, { P = 1.3e-3, f0 = 0.01, tau_p = 25, steps = 20000 })
local iv = require("invasim")
local options = require("lib.options")
local log = require("lib.log")
local motion = require("lib.motion")

local defaults = {
  P = options.ANY,      -- target pressure on the left wall (number or invasim.ramp); 1.3e-3
  kT = 0.0, f0 = 0.0, tau_p = 25.0, gamma = 0.2,
  dt = 0.05, steps = 20000,
  wall_mass = 1.0, wall_gamma = options.OPTIONAL,   -- default: gamma
  barostat = true,      -- false: both walls stay fixed (the box keeps its size; P unused)
  every = 1000,         -- steps between progress updates
  progress = true,
  label = "quench",
}
return function(tissue, opts)
  local o = options.check(opts and opts.label or "quench", opts, defaults)
  for _, key in ipairs{ "kT", "f0", "steps" } do options.at_least(o.label, o, key, 0) end
  if o.P == nil then o.P = 1.3e-3 end
  if type(o.P) ~= "number" and type(o.P) ~= "userdata" then
    options.fail("quench", "key 'P' must be a number or an invasim.ramp{}, got " .. type(o.P))
  end
  local sys = tissue.sys
  local dyn = tissue.dyn
  if not dyn then
    dyn = iv.Dynamics{ dt = o.dt }
    tissue.vertex_method = dyn:add(iv.Damped{ group = tissue.vertices, gamma = o.gamma })
    tissue.cell_method = dyn:add(motion.cell_method(tissue.cells, o))
    if o.barostat then
      dyn:pressure_wall{ P = o.P, mass = o.wall_mass, gamma = o.wall_gamma or o.gamma, walls = tissue.walls }
    end
    tissue.dyn = dyn
  else
    dyn:set_dt(o.dt)
    if dyn:wall_state() then dyn:set_pressure(o.P) end
    tissue.cell_method:set{ gamma = o.gamma }
    if tissue.cell_method:kind() ~= motion.kind(o) then
      options.fail(o.label, "cannot change the kind of cell motion of an existing Dynamics (" ..
                   tissue.cell_method:kind() .. "); run quench first with the motion you want")
    end
    local kind = tissue.cell_method:kind()
    if kind == "Active" then
      tissue.cell_method:set{ f0 = o.f0, tau_p = o.tau_p, kT = o.kT }
    elseif kind == "Langevin" then
      tissue.cell_method:set{ kT = o.kT }
    end
  end
  local wall = dyn:wall_state()
  local walls = wall and string.format("P = %g%s", wall.P, type(o.P) == "userdata" and " (ramp)" or "")
                or "fixed walls"
  log.say(o.label, "%s, %s (%s), %d steps of dt = %g", walls, motion.describe(o),
          tissue.cell_method:kind(), o.steps, dyn:dt())
  if require("lib.resume").pending() then
    log.say(o.label, "steps skipped: resuming from a checkpoint")
    return tissue
  end
  local progress = o.progress and iv.Progress{ total = o.steps, label = o.label } or nil
  dyn:run(sys, o.steps, { every = o.every, progress = progress })
  if progress then progress:finish() end
  local signal = iv.interrupted()
  if signal then
    local dir = require("lib.resume").run_dir()
    error(string.format("stopped by %s during %s at step %d; checkpoints are written during production " ..
                        "only: %s", signal, o.label, sys:step(),
                        dir and "invasim run --resume " .. dir .. " starts the run again from the beginning"
                        or "run the protocol again from the start"), 0)
  end
  local box = sys:box()
  log.say(o.label, "t = %g, L_x = %.4f, phi = %.4f, T_c = %.3e, T_a = %.3e", sys:time(),
          box.lengths[1], sys:packing().total, sys:temperature(tissue.cells),
          sys:temperature(tissue.vertices))
  return tissue
end
