-- The paper's Fig. 9 (Appendix A) at reduced scale: the distribution P(A_2D) of the 2D shape
-- parameter p^2/(4 pi s) of random planar slices through the adipocytes (shapes.csv) for the
-- reference shape parameter A_0 in {1.0, 1.1, 1.3}, at the main job's defaults (beta = 1e-2,
-- tau_p = 25, f0 = 0.002 with the default background), two seeds. A_0 shapes the adipocytes from the start, so every point
-- compresses its own tissue (no shared preparation).
--   invasim sweep init protocols/sweeps/fig9_shapes.lua
--   invasim sweep run out/fig9_shapes --jobs 2
return {
  protocol = "../invasion.lua",
  set = { system = "reduced", P = 1.3e-3, quench_steps = 20000, steps = 150000, every = 1000,
          snapshot_every = 0, checkpoint_every = 20000 },
  product = { A_0 = { 1.0, 1.1, 1.3 } },
  seeds = { 1, 2 },
  tiny = { set = { quench_steps = 100, steps = 400, every = 100, checkpoint_every = 0 },
           take = 2 },
}
