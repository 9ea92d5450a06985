-- The paper's Fig. 4a at the paper's scale: passive repulsive cells (f0 = 0, beta = 0), 28
-- adipocytes and 1500 cells (system = paper), eight temperatures across the transition,
-- 2 k_B T/(P sigma^3) = 0.01 to 1 in the paper's convention (bath kT = that x P / 2), to
-- t = 5e5 (1e7 steps), A_t every 1e4 steps, so that A_n at t = 1e4, 1e5 and 5e5 (the curve
-- moving left in time, and T_g) come from one run per temperature (8 points); one compressed
-- tissue.
--   invasim sweep init protocols/sweeps/paper_scale/fig4a_passive.lua --workspace out/paper_fig4a_passive
--   invasim sweep run out/paper_fig4a_passive --jobs 1 --threads 2      (this machine)
--   invasim sweep submit out/paper_fig4a_passive --slurm --cpus-per-task 2 --time 04:00:00
--   scripts/validation.py plan protocols/sweeps/paper_scale/fig4a_passive.lua  (projected cost)
return {
  protocol = "../../invasion.lua",
  set = { system = "paper", f0 = 0.0, beta = 0.0, P = 1.3e-3,
          quench_steps = 20000, steps = 10000000, every = 10000,
          snapshot_every = 0, checkpoint_every = 100000 },
  -- 2 kT/(P sigma^3) = 0.01, 0.02, 0.03, 0.05, 0.1, 0.2, 0.4, 1
  product = { kT = { 6.5e-6, 1.3e-5, 1.95e-5, 3.25e-5, 6.5e-5, 1.3e-4, 2.6e-4, 6.5e-4 } },
  seeds = { 1 },
  prep = { set = { quench_steps = 0, steps = 0 } },
  tiny = { set = { system = "reduced", quench_steps = 100, steps = 400, every = 100,
                   checkpoint_every = 0 }, take = 2 },
}
