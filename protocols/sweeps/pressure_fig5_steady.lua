-- The six state points of pressure_fig5_long.lua that were still drifting at production
-- t = 50000 (2 k_B T_c/(P sigma^3) ~ 0.8 and 2.6 at the lowest and the middle pressure, ~0.25
-- and 0.8 at the highest), run four times longer again (production t = 2e5), two seeds: a
-- steady answer for E_c ~ 1/P (docs/beyond_the_paper.md, "Pressure").
--   invasim sweep init protocols/sweeps/pressure_fig5_steady.lua
--   invasim sweep run out/pressure_fig5_steady --jobs 2
--   scripts/pressure_sweep.py out/pressure_fig5_steady -o docs/beyond/steady
return {
  protocol = "../invasion.lua",
  set = { system = "reduced", beta = 1e-2, tau_p = 25.0,
          quench_steps = 20000, steps = 4000000, every = 1000,
          snapshot_every = 0, checkpoint_every = 50000 },
  zip = { { P = { 6.5e-4, 6.5e-4, 1.3e-3, 1.3e-3, 2.6e-3, 2.6e-3 },
            f0 = { 0.0025, 0.0043, 0.0035, 0.0061, 0.0028, 0.0049 } } },
  seeds = { 1, 2 },
  prep = { set = { quench_steps = 0, steps = 0 } },
  -- the CI size: three values per axis
  tiny = { set = { quench_steps = 100, steps = 400, every = 100, checkpoint_every = 0 },
           take = 3 },
}
