-- Test: invasim.params seeds math.random through whatever math.randomseed the script has set.
-- A replacement that fails fails invasim.params with its own message (a catchable error; the
-- sanitizer job checks that the C++ frames it crosses are unwound, not skipped), and one that
-- works is called with the seed.
local iv = require("invasim")
local seen
math.randomseed = function(seed)
  seen = seed
  error("randomseed replaced and failing")
end
local ok, err = pcall(iv.params, { seed = 5, x = 2.5 })
assert(not ok and seen == 5, "the replaced math.randomseed was not called with the seed")
assert(tostring(err):find("random_seed_replaced%.lua:%d+: randomseed replaced and failing"), tostring(err))
print("random_seed_replaced: the failing replacement's error came back from invasim.params")
