-- Every integer argument is range-checked before it reaches C++ (no silent
-- truncation to int or size_t); a fractional number is refused. Each refusal names the
-- function, the key (or argument), the value, the allowed range and this file's line.
local iv = require("invasim")
local checks = 0

local function expect_error(pattern, f, ...)
  local ok, err = pcall(f, ...)
  assert(not ok, "expected an error matching " .. pattern)
  assert(type(err) == "string" and err:find(pattern), "wrong message: " .. tostring(err))
  assert(err:find("^integer_ranges%.lua:%d+: "), "no location: " .. err)
  checks = checks + 1
end

local sys = iv.System{ box = {20, 14, 14}, periodic = {false, true, true}, seed = 5 }
-- 2^32 + 5 used to place 5 cells, 1e12 to report "negative number of bodies".
expect_error("place%.cells: key 'n' = 4294967301 is out of range %(must be in %[0, 2147483647%]%)",
             sys.place, sys, { cells = { n = 2^32 + 5, x = {1, 4} } })
expect_error("place%.cells: key 'n' = 4294967301 is out of range", sys.place, sys,
             { cells = { n = 4294967301, x = {1, 4} } })
expect_error("place%.adipocytes: key 'n' = 1e%+12 is out of range %(must be in %[0, 2147483647%]%)",
             sys.place, sys, { adipocytes = { n = 1e12, x = {7, 17} } })
expect_error("place%.cells: key 'n' must be an integer, got 2%.5 %(allowed: in %[0, 2147483647%]%)",
             sys.place, sys, { cells = { n = 2.5, x = {1, 4} } })
assert(sys:n_sites() == 0, "a refused placement placed something")
checks = checks + 1
expect_error("histogram: key 'bins' = 4294967297 is out of range %(must be in %[1, 2147483647%]%)",
             iv.histogram, { 1, 2 }, { lo = 0, hi = 4, bins = 2^32 + 1 })
expect_error("histogram: key 'bins' = 1e%+300 is out of range", iv.histogram, { 1, 2 },
             { lo = 0, hi = 4, bins = 1e300 })
expect_error("slices: key 'per_body' = 4294967298 is out of range %(must be in %[1, 8192%]%)",
             sys.slices, sys, { per_body = 2^32 + 2 })
local cells = sys:place{ cells = { n = 4, x = {1, 4} } }.cells
expect_error("Correlator: key 'lags' = 4294967306 is out of range %(must be in %[1, 2147483647%]%)",
             iv.Correlator, { group = cells, interval = 0.05, lags = 2^32 + 10 })
expect_error("Correlator: key 'origin_every' must be an integer, got 0%.5", iv.Correlator,
             { group = cells, interval = 0.05, origin_every = 0.5 })
expect_error("place%.adipocytes: key 'subdivisions' = 4294967297 is out of range %(must be in %[0, 4%]%)",
             sys.place, sys, { adipocytes = { n = 1, x = {7, 17}, subdivisions = 2^32 + 1 } })
expect_error("Progress: key 'total' = 1e%+300 is out of range %(must be >= 0%)", iv.Progress,
             { total = 1e300 })
expect_error("System: key 'seed' = %-1 is out of range %(must be >= 0%)", iv.System,
             { box = {1, 1, 1}, seed = -1 })
expect_error("compress: key 'max_compressions' must be an integer, got inf", iv.compress, sys,
             { to_phi = 0.5, max_compressions = math.huge })
-- Positional integer arguments.
local ramp = iv.ramp{ from = 0, to = 1, steps = 10 }
expect_error("bad argument #1 to 'value' %(integer >= 0 expected, got %-1%)", function() ramp:value(-1) end)
expect_error("bad argument #1 to 'value' %(integer >= 0 expected, got 1%.5%)", function() ramp:value(1.5) end)
expect_error("bad argument #1 to 'value' %(integer >= 0 expected, got 1e%+300%)", function() ramp:value(1e300) end)
expect_error("bad argument #1 to 'value' %(integer expected, got string%)", function() ramp:value("3") end)
local progress = iv.Progress{ total = 10, live = false, every_seconds = 1e9 }
expect_error("bad argument #1 to 'update' %(integer >= 0 expected, got %-5%)", function() progress:update(-5) end)
local dyn = iv.Dynamics{ dt = 0.01 }
expect_error("bad argument #2 to 'run' %(integer >= 0 expected, got 2%.5%)", function() dyn:run(sys, 2.5) end)
print("integer_ranges: all " .. checks .. " checks passed")
