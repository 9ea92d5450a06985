-- The paper's Fig. 4b inset at the paper's scale, at the paper's temperature: as
-- fig4b_starts.lua, with f0 = 0.00216. fig4b_starts' f0 = 0.0019 measured 2 k_B T_c/(P sigma^3)
-- = 0.233 at this size (about 6.45e4 f0^2), below the paper's ~0.3; this f0 gives ~0.3 by the
-- same factor. De-mixed and mixed start, two seeds each (4 points), to t = 5e5 (1e7 steps of
-- dt = 0.05).
--   invasim sweep init protocols/sweeps/paper_scale/fig4b_starts_hot.lua --workspace out/paper_fig4b_starts_hot
--   invasim sweep run out/paper_fig4b_starts_hot --jobs 1 --threads 2         (this machine)
--   invasim sweep submit out/paper_fig4b_starts_hot --slurm --cpus-per-task 2 --time 04:00:00
--   scripts/validation.py plan protocols/sweeps/paper_scale/fig4b_starts_hot.lua   (projected cost)
return {
  protocol = "../../invasion.lua",
  set = { system = "paper", beta = 1e-2, tau_p = 25.0, P = 1.3e-3, f0 = 0.00216,
          quench_steps = 20000, steps = 10000000, every = 10000,
          snapshot_every = 0, checkpoint_every = 100000 },
  product = { start = { "demixed", "mixed" } },
  seeds = { 1, 2 },
  tiny = { set = { system = "reduced", quench_steps = 100, steps = 400, every = 100,
                   checkpoint_every = 0 }, take = 2 },
}
