-- Test: lib/motion.active_temperature is the free-particle temperature the integrator gives
-- (docs/model.md, "Vertex bath": the default background is a multiple of it). Free active
-- particles (no forces, no noise) in a periodic box, f0 = 0.05, gamma = 0.2, dt = 0.05, at
-- tau_p = 0.02 (shorter than dt: the continuous formula (f0/gamma)^2 tau_p/(3 (tau_p + tau_g))
-- is 1.47 times too small there), 2.5 and 25: the measured m <v^2>/3, averaged over 2000
-- particles and 10000 steps, within 2 % of it.
package.path = "../../protocols/?.lua;" .. package.path
local iv = require("invasim")
local motion = require("lib.motion")
for _, tau_p in ipairs{ 0.02, 2.5, 25.0 } do
  local s = iv.System{ box = { 40, 40, 40 }, periodic = { true, true, true }, seed = 5 }
  s:place{ cells = { n = 2000, x = { 0, 40 } } }
  local cells = s:group("cancer")
  local d = iv.Dynamics{ dt = 0.05 }
  d:add(iv.Active{ group = cells, gamma = 0.2, f0 = 0.05, tau_p = tau_p, kT = 0 })
  d:run(s, 1000)
  local sum, n = 0.0, 0
  for _ = 1, 200 do
    d:run(s, 50)
    sum, n = sum + s:temperature(cells), n + 1
  end
  local measured, expected = sum / n, motion.active_temperature(0.05, tau_p, 0.2, 0.05)
  local continuous = (0.05 / 0.2) ^ 2 * tau_p / (3 * (tau_p + 5))
  print(string.format("tau_p = %g: m<v^2>/3 = %.5g, active_temperature = %.5g (ratio %.4f), continuous formula %.5g",
                      tau_p, measured, expected, measured / expected, continuous))
  assert(math.abs(measured / expected - 1) < 0.02,
         string.format("FAILED: tau_p = %g: measured %.5g against %.5g", tau_p, measured, expected))
end
print("ok: active_temperature is the integrator's free-particle temperature")
