-- The paper's Fig. 3 at the paper's scale: passive repulsive cells, 28 adipocytes and 1500
-- cells (system = paper), the figure's five temperatures 2 k_B T/(P sigma^3) = 1.25e-3,
-- 7.89e-2, 0.125, 0.198, 1.25 (bath kT = that x P / 2), to t = 5e5 (1e7 steps): A_t(t),
-- A_t^min/A_t^max at the paper's size, and slices of the last snapshot: 5 points.
--   invasim sweep init protocols/sweeps/paper_scale/fig3_passive_slices.lua --workspace out/paper_fig3
--   invasim sweep run out/paper_fig3 --jobs 1 --threads 2                (this machine)
--   invasim sweep submit out/paper_fig3 --slurm --cpus-per-task 2 --time 04:00:00
--   scripts/validation.py plan protocols/sweeps/paper_scale/fig3_passive_slices.lua (projected cost)
return {
  protocol = "../../invasion.lua",
  set = { system = "paper", f0 = 0.0, beta = 0.0, P = 1.3e-3,
          quench_steps = 20000, steps = 10000000, every = 10000,
          snapshot_every = 2500000, checkpoint_every = 100000 },
  product = { kT = { 8.125e-7, 5.1285e-5, 8.125e-5, 1.287e-4, 8.125e-4 } },
  seeds = { 1 },
  prep = { set = { quench_steps = 0, steps = 0 } },
  tiny = { set = { system = "reduced", quench_steps = 100, steps = 400, every = 100,
                   snapshot_every = 400, checkpoint_every = 0 }, take = 2 },
}
