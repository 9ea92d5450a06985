-- Used by stop_in_rescale.sh: a small compressed tissue, then the rescale stage with a FIRE
-- that never converges (ftol far below round-off), so that only a signal can end it.
package.path = "../../protocols/?.lua;" .. package.path
local iv = require("invasim")
local p = iv.params{ seed = 1 }
local tissue = require("lib.init"){ N_a = 2, N_c = 20, L0 = 30.0, seed = p.seed }
require("lib.compress")(tissue, { to_phi = 0.3, progress = false })
print("stop_in_rescale: rescaling")
io.stdout:flush()
require("lib.rescale")(tissue, { phi_a = 0.2, ftol = 1e-300, max_steps = 1000000000 })
print("stop_in_rescale: the rescale ended without a signal")
