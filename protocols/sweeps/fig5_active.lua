-- The paper's Fig. 5 at reduced scale: beta in {1e-3, 1e-2} x tau_p in {0.02, 25, 2500}, six
-- self-propulsion forces f0 per tau_p (zipped with it: a persistence of 0.02 needs about 15
-- times the force for the same measured temperature, k_B T_c ~ f0^2 tau_p/(tau_p + tau_g)),
-- spanning 2 k_B T_c/(P sigma^3) ~ 0.01 to 3 (the paper's convention), two seeds (the fit of a and b needs replicates
-- for honest errors, docs/sweeps_analysis.md; a third did not fit the campaign's budget), from
-- one compressed tissue. The production is 4e6 steps (t = 2e5, 0.4 of the paper's 5e5): at
-- 2.5e5 steps, 24 of the 72 runs still drifted (docs/validation.md, "Steady state"). The passive
-- curve of the figure (beta = 1e-2, f0 = 0) is fig5_passive.lua.
-- Active cells carry the protocols' default background temperature (background_factor = 6:
-- T_0 = 6 x the free-particle active temperature T_act, docs/model.md "Vertex bath"), so f0
-- sets both; the measured 2 k_B T_c/(P sigma^3) is about 14 T_act/P in a fluid and 12 T_act/P
-- in a caged tissue, T_act ~ (f0/gamma)^2 tau_p/(3 (tau_p + tau_g)).
--   invasim sweep init protocols/sweeps/fig5_active.lua
--   invasim sweep run out/fig5_active --jobs 2
--   scripts/validation.py figure fig5 out/fig5_active out/fig5_passive -o docs/validation
return {
  protocol = "../invasion.lua",
  set = { system = "reduced", P = 1.3e-3,
          quench_steps = 20000, steps = 4000000, every = 16000,
          snapshot_every = 0, checkpoint_every = 100000 },
  product = { beta = { 1e-3, 1e-2 } },
  zip = { { tau_p = { 25.0, 25.0, 25.0, 25.0, 25.0, 25.0,
                      2500.0, 2500.0, 2500.0, 2500.0, 2500.0, 2500.0,
                      0.02, 0.02, 0.02, 0.02, 0.02, 0.02 },
            f0 = { 0.00035, 0.00061, 0.0011, 0.002, 0.0035, 0.0061,
                   0.00032, 0.00056, 0.001, 0.0018, 0.0032, 0.0056,
                   0.0051, 0.0088, 0.016, 0.028, 0.047, 0.073 } } },
  seeds = { 1, 2 },
  prep = { set = { quench_steps = 0, steps = 0 } },
  -- the CI size: three values per axis, so that the sigmoid fits run in CI too
  tiny = { set = { quench_steps = 100, steps = 400, every = 100, checkpoint_every = 0 },
           take = 3 },
}
