-- Stage "quench" / "equilibrate" (docs/model.md, protocol step 3): the left wall becomes a piston under
-- pressure P, the cells get their thermostat or activity, the vertices their bath (vertex_bath:
-- "langevin" at the background kT, with the piston, or "damped" with vertex_gamma), and the
-- system runs for `steps` steps of dt. It creates tissue.dyn (the Dynamics every later stage
-- runs with); calling it again (equilibrate) replaces the cells' motion and the pressure and
-- keeps the piston's velocity.
--
--   require("lib.quench")(tissue, { P = 1.3e-3, f0 = 0.01, tau_p = 25, steps = 20000 })
local iv = require("invasim")
local declare = require("lib.declare")
local log = require("lib.log")
local motion = require("lib.motion")

-- The keys that set an engine field take its declaration (range, unit, help, default) from
-- the engine (lib/declare.lua); kT and f0 as plain numbers here (the engine also takes Ramps).
local spec = {
  P = declare.engine_keyword("Dynamics.pressure_wall", "P", 1.3e-3),  -- target pressure on the left wall
  kT = declare.engine_keyword("Active", "kT", nil, "number"),
  f0 = declare.engine_keyword("Active", "f0", 0.0, "number"),
  tau_p = declare.engine_keyword("Active", "tau_p", 25.0),
  gamma = declare.engine_keyword("Active", "gamma"),
  vertex_bath = "langevin",   -- "langevin" (noise at kT, vertices and piston) or "damped"
  vertex_gamma = declare.engine_keyword("Langevin", "gamma"),  -- the vertices' damping coefficient
  vertex_mass = { type = "number", range = "(0, inf)" },  -- each vertex's mass (default 1, the cells'); set
                                                  -- by the first quench, a later different one refused
  vertex_kT = 0.0,              -- the langevin vertices' noise temperature (0: the background kT)
  dt = declare.engine_keyword("Dynamics", "dt"), steps = { 20000, type = "number", range = "[0, inf)" },
  wall_mass = iv.Dynamics.pressure_wall.defaults.mass, wall_gamma = { type = "number" },  -- default: gamma
  barostat = true,      -- false: both walls stay fixed (the box keeps its size; P unused)
  every = 1000,         -- steps between progress updates
  progress = true,
  label = "quench",
}
return function(tissue, opts)
  local o = iv.keywords(opts and opts.label or "quench", opts, spec)
  local bad_bath = motion.check_vertex_bath(o.vertex_bath)
  if bad_bath then error(string.format("%s: vertex_bath = '%s': %s", o.label, o.vertex_bath, bad_bath), 2) end
  local bad_kT = motion.check_vertex_kT(o.vertex_bath, o.vertex_kT)
  if bad_kT then error(o.label .. ": " .. bad_kT, 2) end
  local sys = tissue.sys
  local dyn = tissue.dyn
  if not dyn then
    tissue.vertex_mass = o.vertex_mass or 1.0
    sys:set_mass{ group = tissue.vertices, mass = tissue.vertex_mass }
    dyn = iv.Dynamics{ dt = o.dt }
    tissue.vertex_method = dyn:add(motion.vertex_method(tissue.vertices, o))
    tissue.cell_method = dyn:add(motion.cell_method(tissue.cells, o))
    if o.barostat then
      local piston = { P = o.P, mass = o.wall_mass, gamma = o.wall_gamma or o.gamma, walls = tissue.walls }
      if o.vertex_bath == "langevin" then piston.kT = o.kT end  -- damped: no noise (kT = 0)
      dyn:pressure_wall(piston)
    end
    tissue.dyn = dyn
  else
    local vertex_kind = o.vertex_bath == "langevin" and "Langevin" or "Damped"
    if tissue.vertex_method:kind() ~= vertex_kind then
      error(o.label .. ": cannot change the vertex bath of an existing Dynamics (" ..
            tissue.vertex_method:kind() .. " vertices); run quench first with the bath you want", 2)
    end
    if o.vertex_mass and o.vertex_mass ~= tissue.vertex_mass then
      error(string.format("%s: vertex_mass = %g: the vertices' mass was set to %g by the first quench " ..
                          "and cannot change in an existing Dynamics; run quench first with the mass you want",
                          o.label, o.vertex_mass, tissue.vertex_mass), 2)
    end
    dyn:set_dt(o.dt)
    if dyn:wall_state() then
      dyn:set_pressure(o.P)
      if o.vertex_bath == "langevin" then dyn:set_wall_kT(o.kT) end
    end
    tissue.vertex_method:set{ gamma = o.vertex_gamma }
    if vertex_kind == "Langevin" then tissue.vertex_method:set{ kT = motion.vertex_kT(o) } end
    tissue.cell_method:set{ gamma = o.gamma }
    if tissue.cell_method:kind() ~= motion.kind(o) then
      error(o.label .. ": cannot change the kind of cell motion of an existing Dynamics (" ..
            tissue.cell_method:kind() .. "); run quench first with the motion you want", 2)
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
  log.say(o.label, "%s, %s (%s), %d steps of dt = %g; %s", walls, motion.describe(o),
          tissue.cell_method:kind(), o.steps, dyn:dt(), motion.describe_vertices(o, tissue.vertex_mass))
  if require("lib.resume").pending() then
    log.say(o.label, "steps skipped: resuming from a checkpoint")
    return tissue
  end
  local progress = o.progress and iv.Progress{ total = o.steps, label = o.label } or nil
  dyn:run(sys, o.steps, { every = o.every, progress = progress })
  local signal = iv.interrupted()
  if progress then
    if signal then progress:stop() else progress:finish() end
  end
  if signal then
    local resume = require("lib.resume")
    error(string.format("stopped by %s during %s at step %d; no checkpoint is written during a quench " ..
                        "(only during compression and production): %s", signal, o.label, sys:step(),
                        resume.restart_advice()), 0)
  end
  local box = sys:box()
  local T_c, T_a = sys:temperature(tissue.cells), sys:temperature(tissue.vertices)
  -- Both 0 after a quench of no steps (the minimised tissue is at rest): no ratio.
  local ratio = T_a > 0 and string.format("%.3g", T_c / T_a) or ("undefined (T_a = " .. T_a .. ")")
  log.say(o.label, "t = %g, L_x = %.4f, phi = %.4f, T_c = %.3e, T_a = %.3e, T_c/T_a = %s",
          sys:time(), box.lengths[1], sys:packing().total, T_c, T_a, ratio)
  return tissue
end
