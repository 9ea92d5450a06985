-- The paper's Fig. 4b at reduced scale: active cohesive cancer cells (beta = 1e-2, tau_p = 25)
-- with the protocols' default background (background_factor = 6, docs/model.md "Vertex
-- bath"); the self-propulsion f0 sets the measured temperature, seven values of
-- 2 k_B T_c/(P sigma^3) from about 0.03 to 3 (the paper's convention; about 7.5e4 f0^2),
-- denser around the paper's 0.3, three seeds (with two, the error of A_n at 0.3 was
-- too wide to decide the verdict), from one compressed tissue. A_n at several times comes from
-- series.csv (scripts/validation.py figure fig4b); the inset's mixed-start comparison is
-- fig4b_inset.lua.
--   invasim sweep init protocols/sweeps/fig4b_cohesive.lua
--   invasim sweep run out/fig4b_cohesive --jobs 2
return {
  protocol = "../invasion.lua",
  set = { system = "reduced", beta = 1e-2, tau_p = 25.0, P = 1.3e-3,
          quench_steps = 20000, steps = 500000, every = 2000,
          snapshot_every = 0, checkpoint_every = 20000 },
  product = { f0 = { 0.00058, 0.001, 0.0015, 0.002, 0.0026, 0.004, 0.0062 } },
  seeds = { 1, 2, 3 },
  prep = { set = { quench_steps = 0, steps = 0 } },
  tiny = { set = { quench_steps = 100, steps = 400, every = 100, checkpoint_every = 0 },
           take = 2 },
}
