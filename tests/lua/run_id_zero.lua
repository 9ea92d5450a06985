-- Test: -0 is 0 for a run. `--set x=-0` reaches the protocol as 0 (not -0.0), and the run
-- identity (lib/run_identity.lua) of parameters holding -0.0 is that of 0.0. Run with
-- --set x=-0 (tests/lua/CMakeLists.txt).
package.path = "../../protocols/?.lua;" .. package.path
local iv = require("invasim")
local identity = require("lib.run_identity")
local p = iv.params{ x = { 1.0, help = "a number" } }
assert(p.x == 0 and 1 / p.x == math.huge, "--set x=-0 reached the protocol as " .. tostring(p.x))
local zero = identity.of{ P = 0.0, steps = 10 }
local negative = identity.of{ P = -0.0, steps = 10 }
assert(zero.id == negative.id,
       string.format("run ids differ: %s for P = 0.0, %s for P = -0.0\n%s\n%s", zero.id,
                     negative.id, zero.text, negative.text))
assert(identity.format_value(-0.0) == "0", "format_value(-0.0) = " .. identity.format_value(-0.0))
print("run_id_zero: --set x=-0 gives 0; -0.0 and 0.0 give one run id " .. zero.id)
