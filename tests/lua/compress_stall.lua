-- Test: a compression whose FIRE stalls stops with a diagnostic (lib/compress.lua). With an
-- iteration limit of 30 and ftol = 1e-9, the first compression step that brings the bodies
-- into contact cannot converge: the stage must stop there, naming the step, the limit, the
-- residual force and ftol, instead of running every further step to its limit.
package.path = "../../protocols/?.lua;" .. package.path
local tissue = require("lib.init"){ N_a = 2, N_c = 20, L0 = 30.0, seed = 1 }
local ok, err = pcall(require("lib.compress"), tissue,
                      { to_phi = 0.5, ftol = 1e-9, max_steps = 30, progress = false })
assert(not ok, "the stalled compression should have stopped")
print(err)
assert(tostring(err):find("the FIRE of compression step %d+ stopped at its iteration limit " ..
                          "%(max_steps = 30%) with max force [0-9.e+-]+, above ftol = 1e%-09 " ..
                          "%(phi = 0%.%d+%): the minimisation stalled"),
       "not the stall diagnostic: " .. tostring(err))
print("compress_stall: the stalled FIRE stopped the compression")
