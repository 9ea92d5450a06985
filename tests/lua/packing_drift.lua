-- Test: lib.packing_drift, the packing-fraction scan's report of the measured
-- phi_a beside the target, on synthetic production series: the mean over all samples, the
-- first and final values, the warning when the mean is further than `drift` from the target,
-- and its input errors.
package.path = "../../protocols/?.lua;" .. package.path
local drift = require("lib.packing_drift")
local checks = 0

local function check(ok, what)
  if not ok then error("FAILED: " .. what, 2) end
  checks = checks + 1
end

local function result(values)
  local rows = {}
  for i, v in ipairs(values) do rows[i] = { step = 100 * i, phi_a = v } end
  return { series = { rows = rows } }
end

-- Within the default tolerance 0.05: reported, not flagged.
local near = drift(0.6, result{ 0.60, 0.58, 0.57, 0.57 }, { P = 1.3e-3 })
check(math.abs(near.phi_a_mean - 0.58) < 1e-12, "mean over all samples")
check(near.phi_a_first == 0.60 and near.phi_a_final == 0.57 and near.samples == 4, "first, final, samples")
check(near.phi_a_target == 0.6 and not near.drifted and near.drift == 0.05, "not drifted")
-- Far from the target: flagged.
local far = drift(0.9, result{ 0.88, 0.80, 0.78, 0.78 }, { P = 1.3e-3 })
check(far.drifted and math.abs(far.phi_a_mean - 0.81) < 1e-12, "drifted by -0.09")
-- A custom tolerance.
check(drift(0.6, result{ 0.58 }, { drift = 0.01 }).drifted, "drift = 0.01 flags 0.02")
-- Rows without phi_a (another observer set) are an error, as are bad options.
local function expect_error(pattern, ...)
  local ok, err = pcall(drift, ...)
  check(not ok and tostring(err):find(pattern), "error " .. pattern .. " (got " .. tostring(err) .. ")")
end
expect_error("packing: production recorded no phi_a", 0.6, { series = { rows = { { step = 1 } } } })
expect_error("packing: unknown key 'drfit' %(did you mean 'drift'%?%); valid keys: P, drift", 0.6, result{ 0.6 }, { drfit = 0.1 })
expect_error("packing: key 'drift' = %-1 is out of range %(must be > 0%)", 0.6, result{ 0.6 }, { drift = -1 })
expect_error("packing: the target phi_a must be a number, got string", "0.6", result{ 0.6 })
print(string.format("packing_drift: all %d checks passed", checks))
