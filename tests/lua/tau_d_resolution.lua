-- Test: the production stage's default correlator sampling resolves tau_d (C_vv = 1/e). One
-- run samples C_vv every step (0.05 tau apart, the reference); tau_d read from its values
-- only every correlate_every steps (a straight line between samples, as the correlator's
-- decay time does) stays within 0.5 % of the reference at the default correlate_every, and
-- is over 1 % low at 20 steps (1 tau, past tau_d ~ 0.9 tau). Runs of the same trajectory (the
-- correlators do not touch the dynamics) with the defaults and with correlate_every = 20:
-- the summary flags the second's tau_d unresolved (below one sample interval), not the first.
package.path = "../../protocols/?.lua;" .. package.path
local iv = require("invasim")
local parameters = require("lib.parameters")
local stage = require("lib.stages")
local motion = require("lib.motion")
local production = require("lib.production")
local p = iv.params(parameters.merge{})
local N_a, N_c, L0 = parameters.size(p)

local function production_run(correlation)
  local tissue = stage.init(parameters.init_options(p, N_a, N_c, L0))
  stage.compress(tissue, { to_phi = p.phi, ftol = p.compress_ftol, final_ftol = p.final_ftol,
                           progress = false })
  stage.quench(tissue, motion.quench_options(p, { steps = p.quench_steps, progress = false }))
  local o = { steps = p.steps, every = p.every, interface = false, slices_per_body = 0, progress = false }
  for k, v in pairs(correlation) do o[k] = v end
  return stage.production(tissue, o)
end

-- The 1/e crossing of C_vv read from every `stride`-th lag, linear between them.
local function crossing(t, c, stride)
  local level = math.exp(-1)
  for i = 1 + stride, #c, stride do
    if c[i] <= level then
      local j = i - stride
      return t[j] + (c[j] - level) * (t[i] - t[j]) / (c[j] - c[i])
    end
  end
end

local reference = production_run{ correlate_every = 1, lags = 400, origin_every = 100 }
local f = reference.correlator:result().columns
local ref = reference.summary.tau_d
assert(math.abs(crossing(f.t, f.cvv, 1) - ref) <= 1e-12 * ref, "the crossing as the correlator's tau_d")
local every = production.keys.correlate_every[1]
local resolved, coarse = crossing(f.t, f.cvv, every), crossing(f.t, f.cvv, 20)
print(string.format("tau_d: every step %.5g; from every %d steps %.5g (%+.2f %%), every 20 steps %.5g (%+.2f %%)",
                    ref, every, resolved, 100 * (resolved / ref - 1), coarse, 100 * (coarse / ref - 1)))
assert(math.abs(resolved / ref - 1) < 0.005, "the default correlate_every resolves tau_d to 0.5 %")
assert(coarse < 0.99 * ref, "20 steps between samples put tau_d over 1 % low")

local defaults = production_run{}.summary
local unresolved = production_run{ correlate_every = 20, lags = 100, origin_every = 10 }.summary
assert(defaults.T_c.mean == unresolved.T_c.mean and defaults.T_c.mean == reference.summary.T_c.mean,
       "the runs follow the same trajectory")
assert(not reference.summary.tau_d_unresolved and not defaults.tau_d_unresolved and
       not defaults.tau_d_standard_unresolved, "tau_d resolved by the reference and the defaults")
assert(unresolved.tau_d_unresolved == true and unresolved.tau_d_standard_unresolved == true,
       "tau_d below the 20-step interval is flagged unresolved")
print("tau_d_resolution: ok")
