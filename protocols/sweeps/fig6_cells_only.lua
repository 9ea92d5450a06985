-- The paper's Fig. 6: active repulsive cells without adipocytes (protocols/cells_only.lua,
-- periodic box, 500 cells), tau_d against tau_p in {0.02, 0.25, 2.5, 25, 250, 2500} at
-- phi_c = 0 (free particles), 0.3, 0.4 and 0.5 (the paper's values), beside the exact free-particle value tau_d_free.
-- Each tau_p gets its equilibration (max(10 tau_g, 2 tau_p)) and at least 5 correlation
-- windows of 4 tau_d_free (zipped with it); one seed.
--   invasim sweep init protocols/sweeps/fig6_cells_only.lua
--   invasim sweep run out/fig6_cells_only --jobs 2
return {
  protocol = "../cells_only.lua",
  set = { N_c = 500, f0 = 0.01, kT = 0.0, every = 1000, checkpoint_every = 50000 },
  product = { phi_c = { 0.0, 0.3, 0.4, 0.5 } },
  zip = { { tau_p = { 0.02, 0.25, 2.5, 25.0, 250.0, 2500.0 },
            equilibrate_steps = { 1000, 1000, 1000, 1000, 10000, 100000 },
            steps = { 20000, 20000, 20000, 50000, 200000, 1000000 } } },
  seeds = { 1 },
  tiny = { set = { N_c = 100, equilibrate_steps = 100, steps = 2000, every = 100,
                   checkpoint_every = 0 }, take = 2 },
}
