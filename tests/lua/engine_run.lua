-- A tiny system end to end from Lua: place 2 adipocytes and 60 cells, compress to phi = 0.25
-- (loose tolerance, few FIRE steps: quick, not converged), then 200 steps of Langevin cells
-- and damped vertices against a pressure wall; then checks that running in chunks with a
-- callback gives exactly the state of one uninterrupted run.
local iv = require("invasim")

local function build(seed)
  local sys = iv.System{ box = {24, 16, 16}, periodic = {false, true, true}, seed = seed }
  local placed = sys:place{
    cells = { n = 60, diameters = {0.9, 1.1}, x = {1, 5} },
    adipocytes = { n = 2, diameter = 6, vertex_diameter = 2, shape_param = 1.1, x = {9, 20} },
  }
  assert(placed.cells:size() == 60 and placed.vertices:size() == 84)
  sys:add(iv.Walls{ eps = 1 })
  sys:add(iv.Contacts{ alpha = 0.2, beta = 1e-2 })
  sys:add(iv.Shape{ eps_v = 1e3, eps_a = 1 })
  return sys
end

-- Compress.
local sys = build(3)
local phi0 = sys:packing().total
assert(phi0 > 0.02 and phi0 < 0.06, phi0)
local progress = iv.Progress{ total = 0, live = false, every_seconds = 1e9, label = "compress" }
local report = iv.compress(sys, { to_phi = 0.25, step = 0.1, ftol = 1e-4, max_steps = 300, progress = progress })
progress:finish()
assert(math.abs(report.phi - 0.25) < 1e-3 and math.abs(sys:packing().total - 0.25) < 1e-3, report.phi)
assert(report.steps >= 20 and report.fire_steps > 0 and type(report.converged) == "boolean")
local L = sys:box().lengths
assert(math.abs(report.box[1] - L[1]) < 1e-12 and L[2] < 16 and L[2] == L[3])
local phi = sys:packing()
assert(math.abs(phi.cancer + phi.adipocyte - phi.total) < 1e-12)

-- Dynamics with a pressure wall.
local cancer, vertices = sys:group("cancer"), sys:group("vertices")
local dyn = iv.Dynamics{ dt = 0.05 }
dyn:add(iv.Langevin{ group = cancer, gamma = 0.2, kT = 1e-3 })
dyn:add(iv.Damped{ group = vertices, gamma = 0.2 })
dyn:pressure_wall{ P = 1e-3, mass = 1, gamma = 0.2 }
sys:set_velocities{ group = cancer, kT = 1e-3 }
local T0 = sys:temperature(cancer)
assert(T0 > 0.3e-3 and T0 < 3e-3, T0)
local x0 = sys:box().lo[1]
local calls, last = 0, nil
local done = dyn:run(sys, 200, { every = 50, callback = function(step, time)
  calls = calls + 1
  last = step
  assert(math.abs(time - 0.05 * step) < 1e-9)
end })
assert(done == 200 and sys:step() == 200 and calls == 4 and last == 200)
assert(math.abs(sys:time() - 10) < 1e-9)
local Tc, Ta = sys:temperature(cancer), sys:temperature(vertices)
assert(Tc == Tc and Tc > 0 and Tc < 1e-1, Tc)
assert(Ta == Ta and Ta >= 0 and Ta < 1e-1, Ta)
assert(sys:box().lo[1] ~= x0, "the pressure wall moved")
local wall = dyn:wall_state()
assert(wall.P == 1e-3 and wall.force == wall.force)
local e = sys:compute()
assert(e.total == e.total and math.abs(e.total - (e.contact + e.wall + e.shape)) < 1e-12)
-- A callback returning false stops the run.
assert(dyn:run(sys, 100, { every = 10, callback = function() return false end }) == 10)
assert(sys:step() == 210)
-- Run from inside a coroutine, the callback runs on that coroutine (as sim:run's observers do).
local co_seen
local co = coroutine.create(function()
  return dyn:run(sys, 10, { every = 10, callback = function() co_seen = coroutine.running() end })
end)
assert(select(2, coroutine.resume(co)) == 10 and co_seen == co, "the callback ran on another thread")
-- FIRE at the wall's pressure.
local min = iv.Fire{ ftol = 1e-4, max_steps = 200 }:minimize(sys, dyn)
assert(min.steps > 0 and min.energy == min.energy and sys:temperature() == 0)
local r = iv.rescale(sys, { phi_a = sys:packing().adipocyte * 0.9, ftol = 1e-4, max_steps = 100 })
assert(r.steps >= 0 and math.abs(sys:packing().adipocyte / (phi.adipocyte * 0.9) - 1) < 0.05)

-- Chunked runs (callbacks every 7 steps that observe energies) reproduce one uninterrupted run
-- exactly.
local function fingerprint(s)
  return string.format("%.17g %.17g %.17g %d", s:compute().total, s:temperature(), s:box().lo[1], s:step())
end
local function dilute(every)
  local s = build(11)
  local d = iv.Dynamics{ dt = 0.05 }
  d:add(iv.Active{ group = s:group("cancer"), f0 = 0.05, tau_p = 2, kT = 1e-3 })
  d:add(iv.Damped{ group = s:group("vertices") })
  d:pressure_wall{ P = 1e-3 }
  if every then
    d:run(s, 60, { every = every, callback = function() s:compute(); s:temperature() end })
  else
    d:run(s, 60)
  end
  return fingerprint(s)
end
local one, chunked = dilute(nil), dilute(7)
assert(one == chunked, one .. " ~= " .. chunked)

-- Ramps reach the engine: kT, f0 and P follow their ramps step by step from the run's start.
do
  local s = iv.System{ box = {12, 10, 10}, periodic = {false, true, true}, seed = 4 }
  s:place{ cells = { n = 20, x = {1, 11} } }
  s:add(iv.Walls{})
  s:add(iv.Contacts{})
  local half = s:group("cancer"):sites()
  local d = iv.Dynamics{ dt = 0.05 }
  local m = d:add(iv.Langevin{ group = s:group("cancer"), kT = iv.ramp{ from = 0, to = 1e-2, steps = 100 } })
  d:pressure_wall{ P = iv.ramp{ from = 1e-3, to = 3e-3, steps = 200 } }
  d:run(s, 50)
  assert(math.abs(m:params().kT - 5e-3) < 1e-15, "kT ramp: " .. m:params().kT)
  assert(math.abs(d:wall_state().P - 1.5e-3) < 1e-15, "P ramp: " .. d:wall_state().P)
  d:run(s, 200)
  assert(m:params().kT == 1e-2 and d:wall_state().P == 3e-3)
  m:set{ kT = 0 }
  assert(m:params().kT == 0)
  d:run(s, 10)
  assert(m:params().kT == 0, "a number clears the ramp")
  assert(#half == 20)
end

print(string.format("engine_run: ok phi=%.4f L=%.3f Tc=%.3g Ta=%.3g steps=%d", report.phi, L[1], Tc, Ta, sys:step()))
