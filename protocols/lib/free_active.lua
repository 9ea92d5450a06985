-- The free active particle without thermal noise (docs/measurements_dynamics.md, "Time correlators"; Caprini & Marconi
-- 2021): its standard-normalised velocity autocorrelation is exactly
--   C(t) = (tau_g e^{-t/tau_g} - tau_p e^{-t/tau_p}) / (tau_g - tau_p),   tau_g = m / gamma
-- (limit tau_g = tau_p: (1 + t/tau) e^{-t/tau}), and tau_d is where C = 1/e, solved here by
-- bisection (C falls monotonically from 1). protocols/cells_only.lua reports it beside the
-- measured tau_d.
local M = {}

-- C(t) for persistence time tau_p and damping time tau_g.
function M.cvv(t, tau_p, tau_g)
  if math.abs(tau_g - tau_p) <= 1e-12 * math.max(tau_g, tau_p) then
    return (1 + t / tau_g) * math.exp(-t / tau_g)
  end
  return (tau_g * math.exp(-t / tau_g) - tau_p * math.exp(-t / tau_p)) / (tau_g - tau_p)
end

-- The time at which C(t) = 1/e (to 1e-12 relative).
function M.tau_d(tau_p, tau_g)
  assert(tau_p > 0 and tau_g > 0, "free_active.tau_d: tau_p and tau_g must be > 0")
  local target = math.exp(-1)
  local lo, hi = 0.0, math.min(tau_p, tau_g)
  while M.cvv(hi, tau_p, tau_g) > target do lo, hi = hi, 2 * hi end
  while hi - lo > 1e-12 * hi do
    local mid = 0.5 * (lo + hi)
    if M.cvv(mid, tau_p, tau_g) > target then lo = mid else hi = mid end
  end
  return 0.5 * (lo + hi)
end

return M
