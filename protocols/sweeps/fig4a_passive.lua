-- The paper's Fig. 4a at reduced scale: passive, repulsive cancer cells (f0 = 0, beta = 0) at
-- P = 1.3e-3 over a wide range of temperatures k_B T/(P sigma^3) from 0.003 to 3 in the paper's
-- convention (twice the equipartition T_c, docs/model.md "Equations of motion": the bath is
-- kT = that x P / 2), two replicates each, all starting from one compressed tissue (the shared
-- preparation). About 10 minutes on 2 cores (docs/sweeps.md):
--   invasim sweep init protocols/sweeps/fig4a_passive.lua
--   invasim sweep run out/fig4a_passive
--   invasim sweep collect out/fig4a_passive -o out/fig4a_passive/results.csv
return {
  protocol = "../invasion.lua",
  set = { system = "reduced", f0 = 0.0, beta = 0.0, P = 1.3e-3,
          quench_steps = 20000, steps = 250000, every = 1000,
          snapshot_every = 0, checkpoint_every = 10000 },
  -- 2 kT/(P sigma^3) = 0.003, 0.01, 0.03, 0.1, 0.3, 1, 3
  product = { kT = { 1.95e-6, 6.5e-6, 1.95e-5, 6.5e-5, 1.95e-4, 6.5e-4, 1.95e-3 } },
  seeds = { 1, 2 },
  -- the compression only: the points skip it (--from)
  prep = { set = { quench_steps = 0, steps = 0 } },
  -- the CI size (invasim sweep init --tiny): two temperatures, one seed, a few hundred steps
  tiny = { set = { quench_steps = 100, steps = 400, every = 100, checkpoint_every = 0 },
           take = 2 },
}
