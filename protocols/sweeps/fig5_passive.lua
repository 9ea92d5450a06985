-- The passive curve of the paper's Fig. 5: cohesive (beta = 1e-2), passive (f0 = 0) cancer
-- cells at k_B T/(P sigma^3) = 0.01 to 3 in the paper's convention (twice the equipartition
-- T_c: the bath is kT = that x P / 2), two seeds, from one compressed tissue. The production
-- is 4e6 steps (t = 2e5), as in fig5_active.lua.
--   invasim sweep init protocols/sweeps/fig5_passive.lua
--   invasim sweep run out/fig5_passive --jobs 2
return {
  protocol = "../invasion.lua",
  set = { system = "reduced", P = 1.3e-3, beta = 1e-2, f0 = 0.0,
          quench_steps = 20000, steps = 4000000, every = 16000,
          snapshot_every = 0, checkpoint_every = 100000 },
  -- 2 kT/(P sigma^3) = 0.01, 0.03, 0.1, 0.3, 1, 3
  product = { kT = { 6.5e-6, 1.95e-5, 6.5e-5, 1.95e-4, 6.5e-4, 1.95e-3 } },
  seeds = { 1, 2 },
  prep = { set = { quench_steps = 0, steps = 0 } },
  -- the CI size: three values per axis, so that the sigmoid fits run in CI too
  tiny = { set = { quench_steps = 100, steps = 400, every = 100, checkpoint_every = 0 },
           take = 3 },
}
