-- The paper's Fig. 5, tau_p = 2500 curves run four times longer than in fig5_active.lua:
-- production t = 50000 = 20 tau_p (there: 12500 = 5 tau_p, too short for curves that were
-- not yet rising sigmoids). The same beta, f0 and seeds; validation.py's fig5 takes this
-- workspace as its third and uses these curves instead of fig5_active's (which it draws
-- hollow for comparison).
-- Active cells carry the protocols' default background temperature (background_factor = 6:
-- T_0 = 6 x the free-particle active temperature T_act, docs/model.md "Vertex bath"), so f0
-- sets both; the measured 2 k_B T_c/(P sigma^3) is about 14 T_act/P in a fluid and 12 T_act/P
-- in a caged tissue, T_act ~ (f0/gamma)^2 tau_p/(3 (tau_p + tau_g)).
--   invasim sweep init protocols/sweeps/fig5_long.lua
--   invasim sweep run out/fig5_long --jobs 2
--   scripts/validation.py figure fig5 out/fig5_active out/fig5_passive out/fig5_long -o docs/validation
return {
  protocol = "../invasion.lua",
  set = { system = "reduced", P = 1.3e-3, tau_p = 2500.0,
          quench_steps = 20000, steps = 1000000, every = 1000,
          snapshot_every = 0, checkpoint_every = 20000 },
  product = { beta = { 1e-3, 1e-2 },
              f0 = { 0.00032, 0.00056, 0.001, 0.0018, 0.0032, 0.0056 } },
  seeds = { 1, 2 },
  prep = { set = { quench_steps = 0, steps = 0 } },
  -- the CI size: three values per axis, so that the sigmoid fits run in CI too
  tiny = { set = { quench_steps = 100, steps = 400, every = 100, checkpoint_every = 0 },
           take = 3 },
}
