-- invasim.stop() inside a callback the engine calls (a Dynamics run's callback, a Simulation's
-- observer) ends the script there without an error: exit status 0, nothing after it runs.
-- With where = nested, the callback tries to run the System again instead: refused, and the
-- outer run does all its steps.
local iv = require("invasim")
local sys = iv.System{ box = { 24, 16, 16 } }
sys:place{ cells = { n = 40, x = { 1, 5 } } }
sys:add(iv.Walls{})
sys:add(iv.Contacts{})
local dyn = iv.Dynamics{ dt = 0.01 }
dyn:add(iv.Langevin{ group = sys:group("cancer"), kT = 1e-3 })
local where = iv.params{ where = { "callback", choices = { "callback", "observer", "nested" }, help = "which callback stops" } }.where
local calls = 0
local function callback()
  calls = calls + 1
  print(string.format("stop_in_callback: %s call %d at step %d", where, calls, sys:step()))
  if calls == 2 then iv.stop() end
end
if where == "nested" then
  local sim = iv.Simulation{ system = sys, dynamics = dyn }
  local refusals = 0
  local function nested()
    for _, inner in ipairs{ function() return dyn:run(sys, 5) end, function() return sim:run(5) end } do
      local ok, err = pcall(inner)
      assert(not ok and tostring(err):find("the System is running already", 1, true), tostring(err))
      refusals = refusals + 1
    end
  end
  assert(dyn:run(sys, 10, { every = 2, callback = nested }) == 10 and sys:step() == 10)
  sim:observe(nested, { every = 5 })
  assert(sim:run(10) == 10 and sys:step() == 20)
  print(string.format("stop_in_callback: %d runs inside runs refused", refusals))
  return
end
if where == "observer" then
  local sim = iv.Simulation{ system = sys, dynamics = dyn }
  sim:observe(callback, { every = 2 })
  sim:run(10)
else
  dyn:run(sys, 10, { every = 2, callback = callback })
end
print("stop_in_callback: not stopped")
