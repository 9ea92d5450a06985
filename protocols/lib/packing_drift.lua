-- The packing-fraction scan's check (docs/model.md, protocol step 6): the adipocyte packing fraction
-- measured during production beside the scan's target. Under the pressure wall the tissue
-- settles where its wall pressure balances P, which can be far from the target phi_a; a run
-- whose production mean is more than `drift` (absolute, default 0.05: half the 0.1 spacing
-- of the paper's scan points) away from the target says so in its log.
--
--   local d = require("lib.packing_drift")(0.6, result, { P = 1.3e-3 })
--   -> { phi_a_target, phi_a_mean, phi_a_first, phi_a_final, samples, drift, drifted }
local iv = require("invasim")
local log = require("lib.log")

local spec = {
  P = { type = "number", help = "the pressure wall's P, named in the warning" },
  drift = { 0.05, range = "(0, inf)", help = "tolerance of |mean phi_a - target|" },
}

return function(target, result, opts)
  local o = iv.keywords("packing", opts, spec)
  if type(target) ~= "number" then
    error("packing: the target phi_a must be a number, got " .. type(target), 2)
  end
  local rows = result.series.rows
  local sum, n = 0.0, 0
  for _, row in ipairs(rows) do
    if row.phi_a then sum, n = sum + row.phi_a, n + 1 end
  end
  if n == 0 then
    error("packing: production recorded no phi_a (the thermo observer is needed)", 2)
  end
  local d = {
    phi_a_target = target, phi_a_mean = sum / n, phi_a_first = rows[1].phi_a,
    phi_a_final = rows[#rows].phi_a, samples = n, drift = o.drift,
  }
  d.drifted = math.abs(d.phi_a_mean - target) > o.drift
  log.say("packing", "phi_a target %.4f, measured %.4f (mean over %d production samples; first %.4f, final %.4f)",
          target, d.phi_a_mean, n, d.phi_a_first, d.phi_a_final)
  if d.drifted then
    log.say("packing", "WARNING: phi_a drifted %+.4f from the target %.4f (more than %g)%s: this run " ..
            "samples phi_a = %.3f, not %.3f", d.phi_a_mean - target, target, o.drift,
            o.P and string.format(" under the pressure wall at P = %g", o.P) or "", d.phi_a_mean, target)
  end
  return d
end
