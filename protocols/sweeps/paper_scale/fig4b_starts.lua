-- The paper's Fig. 4b inset at the paper's scale: 28 adipocytes and 1500 cancer cells
-- (system = paper), beta = 1e-2, tau_p = 25, f0 = 0.0019 (chosen for 2 k_B T_c/(P sigma^3)
-- ~ 0.3 from the reduced system's calibration, where the paper reads a steady A_n ~ 0.55; at
-- this size it measured 0.233: fig4b_starts_hot.lua runs the paper's 0.3), from the de-mixed
-- and the mixed start, two seeds each (4 points), to t = 5e5 (1e7 steps of dt = 0.05, the
-- paper's length).
-- `start` changes the placement, so every point compresses its own tissue.
--   invasim sweep init protocols/sweeps/paper_scale/fig4b_starts.lua --workspace out/paper_fig4b_starts
--   invasim sweep run out/paper_fig4b_starts --jobs 1 --threads 2         (this machine)
--   invasim sweep submit out/paper_fig4b_starts --slurm --cpus-per-task 2 --time 04:00:00
--   scripts/validation.py plan protocols/sweeps/paper_scale/fig4b_starts.lua   (projected cost)
return {
  protocol = "../../invasion.lua",
  set = { system = "paper", beta = 1e-2, tau_p = 25.0, P = 1.3e-3, f0 = 0.0019,
          quench_steps = 20000, steps = 10000000, every = 10000,
          snapshot_every = 0, checkpoint_every = 100000 },
  product = { start = { "demixed", "mixed" } },
  seeds = { 1, 2 },
  tiny = { set = { system = "reduced", quench_steps = 100, steps = 400, every = 100,
                   checkpoint_every = 0 }, take = 2 },
}
