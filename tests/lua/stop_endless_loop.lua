-- SIGTERM while Lua code runs (tests/lua/stop_endless_loop.sh, one case per --set case=...):
--   loop:     an endless loop at the top level;
--   callback: an endless loop inside an observer of the engine;
--   graceful: the engine's step loop takes the stop, then the script's own stop path runs Lua
--             code for 2 s (longer than the hook gives a stop that no stop point took) and
--             ends with its own message: the hook must leave that path alone;
--   checkpoint: the signal arrives while a checkpoint's Lua state takes 2 s to compose (a long
--             run's state): the checkpoint is finished and the run stops right after it, not
--             cut short by the hook.
local iv = require("invasim")
local p = iv.params{ case = { "loop", help = "loop, callback, graceful or checkpoint" } }

local function say(text)
  print(text)
  io.stdout:flush()
end

local function simulation()
  local sys = iv.System{ box = { 8, 8, 8 }, periodic = { true, true, true }, seed = 1 }
  sys:place{ cells = { n = 4, x = { 0, 8 } } }
  sys:add(iv.Contacts{})
  local dyn = iv.Dynamics{ dt = 0.001 }
  dyn:add(iv.Langevin{ group = sys:group("cancer"), gamma = 0.5, kT = 0.1 })
  return iv.Simulation{ system = sys, dynamics = dyn }
end

if p.case == "loop" then
  say("stop_endless_loop: looping")
  while true do end
elseif p.case == "callback" then
  local sim = simulation()
  sim:observe(function()
    say("stop_endless_loop: looping in a callback")
    while true do end
  end, { every = 10 })
  sim:run(100)
elseif p.case == "graceful" then
  local sim = simulation()
  local said = false
  sim:observe(function()
    if not said then say("stop_endless_loop: running") end
    said = true
  end, { every = 100 })
  local done, signal = sim:run(1000000000000)
  assert(signal == "SIGTERM", "the run ended without a signal after " .. tostring(done) .. " steps")
  local start = iv.clock()
  while iv.clock() - start < 2.0 do end  -- a slow stop path in Lua
  say("stop_endless_loop: the stop path finished")
  error("stopped by " .. signal .. " after the script's own stop path", 0)
end
if p.case == "checkpoint" then
  local sim = simulation()
  iv.make_dirs(iv.out_dir)
  local composed = 0
  sim:checkpoint{ path = iv.out_dir .. "/state.ckpt", every = 100, on_stop = true,
                  extra = function()
                    composed = composed + 1
                    if composed == 2 then
                      say("stop_endless_loop: composing a slow checkpoint")
                      local start = iv.clock()
                      while iv.clock() - start < 2.0 do end
                    end
                    return "state " .. composed
                  end }
  local done, signal = sim:run(1000000000000)
  assert(signal == "SIGTERM", "the run ended without a signal after " .. tostring(done) .. " steps")
  -- The slow checkpoint (step 200) is the stop's: on_stop does not write a second one there.
  assert(composed == 2 and iv.exists(iv.out_dir .. "/state.ckpt"), composed .. " checkpoints composed")
  error("stopped by " .. signal .. " at step " .. done .. "; the slow checkpoint finished", 0)
end
error("unknown case " .. tostring(p.case))
