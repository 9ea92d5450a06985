-- sim:sample refuses, when it is called, a schedule that cannot give the correlator its equal
-- intervals: one not every = N alone, an interval other than N x dt, the same correlator twice.
-- Prints "sample_schedule: passed".
local iv = require("invasim")
local sys = iv.System{ box = { 24, 16, 16 } }
sys:place{ cells = { n = 20, x = { 1, 5 } } }
local dyn = iv.Dynamics{ dt = 0.01 }
dyn:add(iv.Langevin{ group = sys:group("cancer"), kT = 1e-3 })
local sim = iv.Simulation{ system = sys, dynamics = dyn }
local c = iv.Correlator{ group = sys:group("cancer"), interval = 0.05, lags = 4 }
local function refused(pattern, schedule)
  local ok, err = pcall(sim.sample, sim, c, schedule)
  assert(not ok and tostring(err):find(pattern, 1, true), tostring(err))
end
refused("its schedule is {every = N} (and a phase) alone, not at steps 5, 10", { at = { 5, 10 } })
refused("alone, not every 5 steps or at the end", { every = 5, at_end = true })
refused("every = 4 steps of dt = 0.01 is 0.04, not the correlator's interval 0.05: make them " ..
        "equal (every = 5)", { every = 4 })
sim:sample(c, { every = 5 })
refused("this correlator is sampled by this Simulation already (every 5 steps)", { every = 5, phase = 1 })
assert(sim:run(20) == 20 and c:samples() == 4)
print("sample_schedule: passed")
