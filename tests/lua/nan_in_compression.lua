-- Test: the blow-up guard fires inside the compression's FIRE. Run with
-- INVASIM_TEST_NAN_AT_COMPRESSION_STEP=3 (setup/test_hooks.hpp: site 0's position becomes NaN
-- at compression step 3); the compression must stop with the guard's diagnostic (FIRE
-- iteration, site, value) instead of minimising NaNs. (Production: production_blowup.lua.)
package.path = "../../protocols/?.lua;" .. package.path
local iv = require("invasim")
local tissue = require("lib.init"){ N_a = 2, N_c = 20, L0 = 30.0, seed = 1 }
local ok, err = pcall(require("lib.compress"), tissue, { to_phi = 0.5, progress = false })
assert(not ok, "the compression with a NaN position should have stopped")
print(err)
assert(tostring(err):find("compress%.lua:%d+: FIRE iteration %d+: blow%-up at step %d+: site 0 %(.-%) has a non%-finite position %(nan"),
       "not the blow-up guard's diagnostic: " .. tostring(err))
print("nan_in_compression: the blow-up guard stopped the compression")
