-- The paper's Figs. 7a and 7b at the paper's scale, for a cluster: tethered tissue
-- (../../tethered.lua), 28 adipocytes and 1500 cells (system = paper), K_ecm in {0, 0.01, 0.04,
-- 0.16} x five f0 (2 k_B T_c/(P sigma^3) ~ 0.03 to 3 with the default background) for both
-- panels, 7a (tau_p = 25, beta = 1e-2) and 7b (tau_p = 2500, beta = 1e-3), two seeds, to
-- t = 5e5 (1e7 steps): 80 points from one compressed tissue.
--   invasim sweep init protocols/sweeps/paper_scale/fig7_tethered.lua --workspace out/paper_fig7
--   invasim sweep submit out/paper_fig7 --slurm --cpus-per-task 2 --time 04:00:00 --array-limit 64
--   scripts/validation.py plan protocols/sweeps/paper_scale/fig7_tethered.lua (projected cost)
return {
  protocol = "../../tethered.lua",
  set = { system = "paper", P = 1.3e-3,
          quench_steps = 20000, equilibrate_steps = 10000, steps = 10000000, every = 10000,
          snapshot_every = 0, checkpoint_every = 100000 },
  product = { K_ecm = { 0.0, 0.01, 0.04, 0.16 } },
  zip = { { tau_p = { 25.0, 25.0, 25.0, 25.0, 25.0, 2500.0, 2500.0, 2500.0, 2500.0, 2500.0 },
            beta = { 1e-2, 1e-2, 1e-2, 1e-2, 1e-2, 1e-3, 1e-3, 1e-3, 1e-3, 1e-3 },
            f0 = { 0.00058, 0.0012, 0.002, 0.0033, 0.0062, 0.00051,
                   0.0011, 0.0018, 0.0029, 0.0056 } } },
  seeds = { 1, 2 },
  prep = { set = { quench_steps = 0, equilibrate_steps = 0, steps = 0 } },
  tiny = { set = { system = "reduced", quench_steps = 100, equilibrate_steps = 100, steps = 400,
                   every = 100, checkpoint_every = 0 }, take = 2 },
}
