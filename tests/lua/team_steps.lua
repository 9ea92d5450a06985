-- The thread-count tests' expectation (checkpoint_continuation.lua, lipolysis.lua,
-- proliferation.lua): with more than one thread CTest sets INVASIM_TEST_TEAM_STEPS=1
-- (src/integrate/test_hooks.hpp), and every step of a System of 1024 sites or more then runs
-- in the parallel team; with one thread none does. Refuses more threads without the hook, so
-- that losing it fails instead of testing nothing. Returns expected(n): how many of n steps
-- must count in dyn:parallel_steps().
local iv = require("invasim")
local team = iv.threads() > 1
assert(not team or os.getenv("INVASIM_TEST_TEAM_STEPS") == "1", "more than one thread needs INVASIM_TEST_TEAM_STEPS=1")
return function(n) return team and n or 0 end
