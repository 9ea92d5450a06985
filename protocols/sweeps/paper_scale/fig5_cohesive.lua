-- The beta = 1e-2, tau_p = 25 curve of the paper's Fig. 5 at the paper's scale: 28 adipocytes
-- and 1500 cells (system = paper), seven f0 spanning 2 k_B T_c/(P sigma^3) ~ 0.03 to 3 with
-- the default background (about 7.5e4 f0^2; docs/model.md "Vertex bath"), to t = 5e5
-- (1e7 steps), one compressed tissue: 7 points.
--   invasim sweep init protocols/sweeps/paper_scale/fig5_cohesive.lua --workspace out/paper_fig5_cohesive
--   invasim sweep run out/paper_fig5_cohesive --jobs 1 --threads 2       (this machine)
--   invasim sweep submit out/paper_fig5_cohesive --slurm --cpus-per-task 2 --time 04:00:00
--   scripts/validation.py plan protocols/sweeps/paper_scale/fig5_cohesive.lua (projected cost)
return {
  protocol = "../../invasion.lua",
  set = { system = "paper", beta = 1e-2, tau_p = 25.0, P = 1.3e-3,
          quench_steps = 20000, steps = 10000000, every = 10000,
          snapshot_every = 0, checkpoint_every = 100000 },
  product = { f0 = { 0.00061, 0.0011, 0.0016, 0.0019, 0.0025, 0.0035, 0.0061 } },
  seeds = { 1 },
  prep = { set = { quench_steps = 0, steps = 0 } },
  tiny = { set = { system = "reduced", quench_steps = 100, steps = 400, every = 100,
                   checkpoint_every = 0 }, take = 2 },
}
