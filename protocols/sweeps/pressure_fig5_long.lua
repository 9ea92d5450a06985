-- The upper half of pressure_fig5.lua run four times longer (production t = 50000): at
-- 2 k_B T_c/(P sigma^3) ~ 0.25, 0.8 and 2.6, where A_t/A_t^max rises and the 250000-step runs
-- still drift, for the three pressures, two seeds. scripts/pressure_sweep.py finds the
-- onsets from its steady points (docs/beyond_the_paper.md).
--   invasim sweep init protocols/sweeps/pressure_fig5_long.lua
--   invasim sweep run out/pressure_fig5_long --jobs 2
--   scripts/pressure_sweep.py out/pressure_fig5_long -o docs/beyond/long
return {
  protocol = "../invasion.lua",
  set = { system = "reduced", beta = 1e-2, tau_p = 25.0,
          quench_steps = 20000, steps = 1000000, every = 1000,
          snapshot_every = 0, checkpoint_every = 20000 },
  zip = { { P = { 6.5e-4, 6.5e-4, 6.5e-4, 1.3e-3, 1.3e-3, 1.3e-3, 2.6e-3, 2.6e-3, 2.6e-3 },
            f0 = { 0.0014, 0.0025, 0.0043, 0.002, 0.0035, 0.0061, 0.0028, 0.0049, 0.0086 } } },
  seeds = { 1, 2 },
  prep = { set = { quench_steps = 0, steps = 0 } },
  -- the CI size: three values per axis
  tiny = { set = { quench_steps = 100, steps = 400, every = 100, checkpoint_every = 0 },
           take = 3 },
}
