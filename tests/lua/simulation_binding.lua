-- Test: iv.Simulation (src/run/ through lua/bind_simulation.cpp): operations on their own
-- schedules (every with phase, at, at_end), in the order added, listed by sim:operations();
-- an observer returning false ends the run; a Simulation run equals a plain dyn:run bit for
-- bit; bad schedules are refused with a message naming the key; operations, methods and the
-- pressure wall cannot change during a run; a Simulation of another System's methods is refused.
local iv = require("invasim")

local function tissue()
  local sys = iv.System{ box = { 12, 12, 12 }, periodic = { true, true, true }, seed = 4 }
  sys:place{ cells = { n = 20, x = { 0, 12 } } }
  sys:add(iv.Contacts{})
  local dyn = iv.Dynamics{ dt = 0.01 }
  dyn:add(iv.Langevin{ group = sys:group("cancer"), gamma = 0.5, kT = 0.1 })
  return sys, dyn
end

local sys, dyn = tissue()
local sim = iv.Simulation{ system = sys, dynamics = dyn }
local log = {}
sim:observe(function(step) log[#log + 1] = "a" .. step end, { every = 4, phase = 1 })
sim:observe(function(step) log[#log + 1] = "b" .. step end, { at = { 6, 2 }, at_end = true })
local listed = table.concat(sim:operations(), "; ")
assert(listed == "observer: every 4 steps (phase 1); observer: at steps 2, 6 or at the end", listed)
local done, signal = sim:run(10)
assert(done == 10 and signal == nil, "run returned " .. tostring(done) .. ", " .. tostring(signal))
local got = table.concat(log, " ")
assert(got == "a1 b2 a5 b6 a9 b10", got)

-- returning false stops the run at that step
local stopper = iv.Simulation{ system = sys, dynamics = dyn }
stopper:observe(function(step) return step < 30 end, { every = 5 })
assert(stopper:run(100) == 20, "stopped after 20 steps (at step 30)")
assert(sys:step() == 30)

-- the same trajectory as dyn:run, bit for bit
local sys2, dyn2 = tissue()
local sim2 = iv.Simulation{ system = sys2, dynamics = dyn2 }
sim2:observe(function() sys2:compute() end, { every = 3 })
sim2:run(30)
local sys3, dyn3 = tissue()
dyn3:run(sys3, 30)
local a, b = sys2:positions(), sys3:positions()
for i = 1, #a do
  for k = 1, 3 do assert(a[i][k] == b[i][k], "site " .. i .. " differs") end
end

-- refused schedules
local function refused(fn, pattern)
  local ok, err = pcall(fn)
  assert(not ok and tostring(err):find(pattern), "expected '" .. pattern .. "', got " .. tostring(err))
end
refused(function() sim:observe(function() end, {}) end, "observe: no schedule; give at least one of every = N")
refused(function() sim:observe(function() end, { phase = 1 }) end, "observe: key 'phase' needs key 'every'")
refused(function() sim:observe(function() end, { every = 3, phase = 3 }) end, "phase = 3 must be in %[0, 3%)")
refused(function() sim:observe(function() end, { every = 0 }) end, "every")
refused(function() sim:observe(function() end, { at = { 1.5 } }) end, "key 'at%[1%]' must be an integer step >= 0")
refused(function() sim:observe(function() end, { at = {} }) end, "observe: key 'at' lists no step")
-- a Dynamics without methods (and no pressure wall) would move nothing: refused, not run
refused(function() iv.Dynamics{ dt = 0.01 }:run(sys, 10) end,
        "run: the Dynamics has no methods, so nothing would move")
-- a return that is neither nil nor a boolean is a mistaken stop: an error, not a run that goes on
local mistaken = iv.Simulation{ system = sys, dynamics = dyn }
mistaken:observe(function() return "stop" end, { every = 5 })
refused(function() mistaken:run(100) end,
        "observer: the function returned a string; return false to stop the run")
refused(function() sim:observe(function() end, { evry = 3 }) end, "unknown key 'evry'")
-- the operations, the methods and the pressure wall of a run are fixed while it runs: a change
-- from one of its operations is refused, and the run ends with that error
local growing = iv.Simulation{ system = sys, dynamics = dyn }
growing:observe(function() growing:observe(function() end, { every = 1 }) end, { every = 4 })
refused(function() growing:run(10) end,
        "observe: Simulation: the observer cannot be added while the Simulation runs")
local adding = iv.Simulation{ system = sys, dynamics = dyn }
adding:observe(function() dyn:add(iv.Damped{ group = sys:group("cancer"), gamma = 1 }) end, { every = 4 })
refused(function() adding:run(10) end, "add: the Dynamics is running %(this call comes from a callback of its run%)")
refused(function() dyn:run(sys, 10, { every = 2, callback = function() dyn:pressure_wall{ P = 0.01 } end }) end,
        "pressure_wall: the Dynamics is running")
assert(#dyn:methods() == 1, "the refused add added nothing")
-- after the run returns, the same changes are taken
local after = iv.Simulation{ system = sys, dynamics = dyn }
after:run(1)
after:observe(function() end, { every = 1 })
assert(#after:operations() == 1)
-- a Dynamics whose methods move another System's sites: refused when the Simulation is made
local other_sys, other_dyn = tissue()
refused(function() iv.Simulation{ system = sys, dynamics = other_dyn } end,
        "Simulation: Langevin: group 'cancer' belongs to another System")
assert(other_sys)
refused(function() iv.Simulation{ system = sys } end,
        "Simulation: missing required key 'dynamics' %(a Dynamics%)")
refused(function() iv.Simulation{ system = sys, dynamics = 1 } end,
        "Simulation: key 'dynamics' must be a Dynamics, got number")
print("simulation_binding: ok")
