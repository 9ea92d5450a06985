-- The whole of the paper's Fig. 5 at the paper's scale, for a cluster: 28 adipocytes and 1500
-- cells (system = paper), beta in {1e-4, 1e-3, 1e-2} x tau_p in {0.02, 25, 250, 2500}, six f0
-- per tau_p spanning 2 k_B T_c/(P sigma^3) ~ 0.01 to 3 with the default background (as in
-- ../fig5_active.lua), two seeds, to t = 5e5 (1e7 steps): 144 points from one compressed
-- tissue. The passive curve is ../fig5_passive.lua with --set system=paper.
--   invasim sweep init protocols/sweeps/paper_scale/fig5_all_curves.lua --workspace out/paper_fig5
--   invasim sweep submit out/paper_fig5 --slurm --cpus-per-task 2 --time 04:00:00 --array-limit 64
--   scripts/validation.py plan protocols/sweeps/paper_scale/fig5_all_curves.lua (projected cost)
return {
  protocol = "../../invasion.lua",
  set = { system = "paper", P = 1.3e-3,
          quench_steps = 20000, steps = 10000000, every = 10000,
          snapshot_every = 0, checkpoint_every = 100000 },
  product = { beta = { 1e-4, 1e-3, 1e-2 } },
  zip = { { tau_p = { 0.02, 0.02, 0.02, 0.02, 0.02, 0.02,
                      25.0, 25.0, 25.0, 25.0, 25.0, 25.0,
                      250.0, 250.0, 250.0, 250.0, 250.0, 250.0,
                      2500.0, 2500.0, 2500.0, 2500.0, 2500.0, 2500.0 },
            f0 = { 0.0051, 0.0088, 0.016, 0.028, 0.047, 0.073,
                   0.00035, 0.00061, 0.0011, 0.002, 0.0035, 0.0061,
                   0.00033, 0.00056, 0.001, 0.0018, 0.0033, 0.0056,
                   0.00032, 0.00056, 0.001, 0.0018, 0.0032, 0.0056 } } },
  seeds = { 1, 2 },
  prep = { set = { quench_steps = 0, steps = 0 } },
  tiny = { set = { system = "reduced", quench_steps = 100, steps = 400, every = 100,
                   checkpoint_every = 0 }, take = 2 },
}
