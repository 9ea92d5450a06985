-- The lowest pressure's hottest state point of pressure_fig5_steady.lua (2 k_B T_c/(P sigma^3)
-- ~ 2.6 at P = 6.5e-4), still rising at production t = 2e5, run to t = 5e5 (the paper's
-- duration), two seeds: with it steady, every pressure's onset rests on steady points
-- (docs/beyond_the_paper.md, "Pressure").
--   invasim sweep init protocols/sweeps/pressure_fig5_lowest.lua
--   invasim sweep run out/pressure_fig5_lowest --jobs 2
--   scripts/pressure_sweep.py out/pressure_fig5 out/pressure_fig5_long \
--     out/pressure_fig5_steady out/pressure_fig5_lowest -o docs/beyond/steady
return {
  protocol = "../invasion.lua",
  set = { system = "reduced", beta = 1e-2, tau_p = 25.0,
          quench_steps = 20000, steps = 10000000, every = 1000,
          snapshot_every = 0, checkpoint_every = 100000 },
  zip = { { P = { 6.5e-4 }, f0 = { 0.0043 } } },
  seeds = { 1, 2 },
  prep = { set = { quench_steps = 0, steps = 0 } },
  -- the CI size
  tiny = { set = { quench_steps = 100, steps = 400, every = 100, checkpoint_every = 0 } },
}
