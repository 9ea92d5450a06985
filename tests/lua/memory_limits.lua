-- Test: parameters that size memory are checked before anything is allocated; the
-- error names the parameter, its value, the bytes it needs and the limit (the memory available,
-- core/memory_budget.hpp), instead of std::bad_alloc after a minute or the OOM killer.
local iv = require("invasim")
local checks = 0
local function refused(pattern, f, ...)
  local ok, err = pcall(f, ...)
  assert(not ok, "expected an error matching " .. pattern)
  assert(tostring(err):find(pattern), tostring(err))
  assert(tostring(err):find("^memory_limits%.lua:%d+: "), "no location: " .. tostring(err))
  checks = checks + 1
end
local limit = "needs about [%d.]+ [KMGTPE]?i?B of memory %([%d.]+ bytes each%); the limit is [%d.]+ [KMGTPE]?i?B %("

refused("histogram: bins = 2147483647 " .. limit, iv.histogram, { 0.5 }, { lo = 0, hi = 1, bins = 2147483647 })

local sys = iv.System{ box = { 8, 8, 8 }, periodic = { true, true, true }, seed = 2 }
refused("placement: cells.n = 2147483647 " .. limit, sys.place, sys, { cells = { n = 2147483647, x = { 0, 8 } } })
refused("placement: adipocytes.n = 100000000 " .. limit, sys.place, sys,
        { adipocytes = { n = 100000000, subdivisions = 4, x = { 0, 8 } } })
assert(sys:n_sites() == 0, "nothing placed")
local big = iv.System{ box = { 40, 40, 40 }, periodic = { true, true, true }, seed = 2 }
refused("volume_grid = 0.0001 gives [%d.e+]+ grid points .*; the limit is 1e%+08 points, i%.e%. volume_grid >= 0%.0",
        big.place, big, { adipocytes = { n = 1, volume_grid = 1e-4, x = { 10, 30 } } })

sys:place{ cells = { n = 4, x = { 0, 8 } } }
refused("time correlator: lags = 2147483647 " .. limit, iv.Correlator,
        { group = sys:group("cancer"), interval = 0.01, lags = 2147483647, origin_every = 1 })

-- Within the limits all of these work.
assert(#iv.histogram({ 0.5 }, { lo = 0, hi = 1, bins = 1000 }).counts == 1000)
big:place{ adipocytes = { n = 1, x = { 10, 30 } } }
print("memory_limits: all " .. checks .. " refused before allocating")
