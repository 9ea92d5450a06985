-- Test: a short passive run under the pressure wall. After a quench, the time average
-- of the pressure the sites exert on the fixed right wall equals the piston's target P within
-- its error bar (3 standard errors, so that the test checks the physics and
-- not the luck of one seed: by momentum balance <F_right> = P L_y L_z exactly in steady state).
-- The error bar itself must be below 5 % of P (measured: 2.4 %, 3.07e-5 for P = 1.3e-3), so
-- that 3 error bars stay below 15 % of P and a pressure wrong by 20 % fails.
package.path = "../../protocols/?.lua;" .. package.path
local iv = require("invasim")
local p = iv.params{ seed = 2, P = 1.3e-3, kT = 5e-4, quench_steps = 50000, steps = 60000, every = 50 }

local tissue = require("lib.init"){ N_a = 4, N_c = 200, L0 = 36.5, seed = p.seed, beta = 0.0 }
require("lib.compress")(tissue, { to_phi = 0.72, progress = false })
require("lib.quench")(tissue, { P = p.P, kT = p.kT, steps = p.quench_steps, progress = false })
local result = require("lib.production")(tissue, { steps = p.steps, every = p.every,
                                                   average_fraction = 1.0, progress = false })
local s = result.summary
local P_right, err = s.P_right.mean, s.P_right.error
print(string.format("P_right = %.5e +- %.2e (target %.3e, %d samples); P_left = %.5e +- %.2e; T_c = %.4e",
                    P_right, err, p.P, s.samples, s.P_left.mean, s.P_left.error, s.T_c.mean))
assert(err > 0 and err < 0.05 * p.P,
       string.format("FAILED: the error bar %.3e is not below 5 %% of P (%.3e)", err, 0.05 * p.P))
assert(math.abs(P_right - p.P) < 3 * err,
       string.format("FAILED: |P_right - P| = %.3e exceeds 3 error bars (%.3e)", math.abs(P_right - p.P), 3 * err))
-- The thermostat works in the dense tissue too: T_c is kT within 5 %.
assert(math.abs(s.T_c.mean / p.kT - 1) < 0.05, "FAILED: T_c = " .. s.T_c.mean .. " is not kT = " .. p.kT)
print("ok: wall pressure averages to P within its error bar")
