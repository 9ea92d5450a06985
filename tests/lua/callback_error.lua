-- An error raised in a callback that a binding runs (a Dynamics callback inside another's):
-- --traceback shows the stack where it was raised, the callbacks' frames included, not only
-- the binding that re-raised it. With --set stale=true the callback's error is caught by
-- pcall first, and a later plain error shows its own traceback, without the callback's.
local iv = require("invasim")
local p = iv.params{ stale = { false, help = "catch the callback's error, then fail elsewhere" } }
local function tissue() local s = iv.System{ box = { 10, 10, 10 } }; s:place{ cells = { n = 10, x = { 1, 9 } } }
  local d = iv.Dynamics{ dt = 0.01 }; d:add(iv.Langevin{ group = s:group("cancer"), kT = 1e-3, gamma = 1 }); return s, d end
local sys, dyn = tissue()
local sys2, dyn2 = tissue()  -- the inner run's: a run inside a run of the same System is refused
local function deepest_frame() error("raised in the inner callback") end
local function inner_callback() deepest_frame() end
local function outer_callback() dyn2:run(sys2, 10, { every = 5, callback = inner_callback }) end
local function run_with_callbacks() dyn:run(sys, 10, { every = 5, callback = outer_callback }) end
if p.stale then
  assert(not pcall(run_with_callbacks))
  local function plain_failure() error("a plain error after the caught one") end
  plain_failure()
else
  run_with_callbacks()
end
