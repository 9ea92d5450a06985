-- A 2 x 2 corner of the paper's Fig. 5 at reduced scale: active cohesive cancer cells with
-- beta in {1e-3, 1e-2} and tau_p in {25, 250}; along each curve the self-propulsion f0 sets
-- the measured temperature k_B T_c/(P sigma^3) (the paper's knob for active runs,
-- docs/model.md), all from one compressed tissue (the shared preparation). Nine f0 values
-- from 0.00036 to 0.0062, denser between 0.0012 and 0.0026 where the cohesive (beta = 1e-2)
-- cells melt, x 3 seeds = 108 points, about 60 minutes on 2 cores (docs/sweeps.md):
--   invasim sweep init protocols/sweeps/fig5_corner.lua
--   invasim sweep run out/fig5_corner
--   invasim sweep collect out/fig5_corner -o out/fig5_corner/results.csv
return {
  protocol = "../invasion.lua",
  set = { system = "reduced", P = 1.3e-3,
          quench_steps = 20000, steps = 250000, every = 1000,
          snapshot_every = 0, checkpoint_every = 10000 },
  product = { beta = { 1e-3, 1e-2 }, tau_p = { 25.0, 250.0 },
              f0 = { 0.00036, 0.00058, 0.00088, 0.0012, 0.0016, 0.002, 0.0026, 0.004, 0.0062 } },
  seeds = { 1, 2, 3 },
  prep = { set = { quench_steps = 0, steps = 0 } },
  tiny = { set = { quench_steps = 100, steps = 400, every = 100, checkpoint_every = 0 },
           take = 2 },
}
