-- The paper's Fig. 4b at reduced scale: active cohesive cancer cells (beta = 1e-2, tau_p = 25,
-- no bath noise: kT = 0); the self-propulsion f0 sets the measured temperature
-- k_B T_c/(P sigma^3) (docs/model.md), seven values from about 0.005 to 3 (paper's convention,
-- from docs/data/sweeps/fig5_results.csv), three seeds (with two, the error of A_n at 0.3 was
-- too wide to decide the verdict), from one compressed tissue. A_n at several times comes from
-- series.csv (scripts/validation.py figure fig4b); the inset's mixed-start comparison is
-- fig4b_inset.lua.
--   invasim sweep init protocols/sweeps/fig4b_cohesive.lua
--   invasim sweep run out/fig4b_cohesive --jobs 2
return {
  protocol = "../invasion.lua",
  set = { system = "reduced", beta = 1e-2, tau_p = 25.0, kT = 0.0, P = 1.3e-3,
          quench_steps = 20000, steps = 500000, every = 2000,
          snapshot_every = 0, checkpoint_every = 20000 },
  product = { f0 = { 0.0045, 0.0075, 0.0095, 0.011, 0.0125, 0.014, 0.02 } },
  seeds = { 1, 2, 3 },
  prep = { set = { quench_steps = 0, steps = 0 } },
  tiny = { set = { quench_steps = 100, steps = 400, every = 100, checkpoint_every = 0 },
           take = 2 },
}
