-- The paper's Fig. 5 curves that fig5_active.lua leaves out, at reduced scale: the weakest
-- cohesion beta = 1e-4 (the figure's triangles) at tau_p = 0.02 and 25, and the persistence
-- tau_p = 250 (magenta) at beta = 1e-3 and 1e-2; six self-propulsion forces f0 per curve
-- (zipped with it, as in fig5_active.lua: the measured 2 k_B T_c/(P sigma^3) ~ 0.01 to 3), two
-- seeds, from one compressed tissue.
-- Active cells carry the protocols' default background temperature (background_factor = 3:
-- T_0 = 3 x the free-particle active temperature, docs/model.md "Vertex bath"), so f0 sets
-- both; the measured 2 k_B T_c/(P sigma^3) is about 8 T_act/P = 8 (f0/gamma)^2 tau_p/(3 (tau_p + tau_g) P).
--   invasim sweep init protocols/sweeps/fig5_extra_curves.lua
--   invasim sweep run out/fig5_extra_curves --jobs 2
--   scripts/validation.py figure fig5 out/fig5_active out/fig5_passive out/fig5_long out/fig5_extra_curves -o docs/validation
return {
  protocol = "../invasion.lua",
  set = { system = "reduced", P = 1.3e-3,
          quench_steps = 20000, steps = 250000, every = 1000,
          snapshot_every = 0, checkpoint_every = 20000 },
  zip = { { beta = { 1e-4, 1e-4, 1e-4, 1e-4, 1e-4, 1e-4,
                     1e-4, 1e-4, 1e-4, 1e-4, 1e-4, 1e-4,
                     1e-3, 1e-3, 1e-3, 1e-3, 1e-3, 1e-3,
                     1e-2, 1e-2, 1e-2, 1e-2, 1e-2, 1e-2 },
            tau_p = { 0.02, 0.02, 0.02, 0.02, 0.02, 0.02,
                      25.0, 25.0, 25.0, 25.0, 25.0, 25.0,
                      250.0, 250.0, 250.0, 250.0, 250.0, 250.0,
                      250.0, 250.0, 250.0, 250.0, 250.0, 250.0 },
            f0 = { 0.007, 0.012, 0.022, 0.038, 0.065, 0.1,
                   0.00048, 0.00084, 0.0015, 0.0027, 0.0048, 0.0084,
                   0.00045, 0.00077, 0.0014, 0.0024, 0.0045, 0.0077,
                   0.00045, 0.00077, 0.0014, 0.0024, 0.0045, 0.0077 } } },
  seeds = { 1, 2 },
  prep = { set = { quench_steps = 0, steps = 0 } },
  -- the CI size: three points, so that the figure's code runs in CI too
  tiny = { set = { quench_steps = 100, steps = 400, every = 100, checkpoint_every = 0 },
           take = 3 },
}
