-- The paper's Fig. 5 curves that fig5_active.lua leaves out, at reduced scale: the weakest
-- cohesion beta = 1e-4 (the figure's triangles) at tau_p = 0.02 and 25, and the persistence
-- tau_p = 250 (magenta) at beta = 1e-3 and 1e-2; six self-propulsion forces f0 per curve
-- (zipped with it, as in fig5_active.lua: the measured 2 k_B T_c/(P sigma^3) ~ 0.01 to 3), two
-- seeds, from one compressed tissue. The production is 4e6 steps (t = 2e5), as in
-- fig5_active.lua: at 2.5e5 steps, 18 of the 48 runs still drifted.
-- Active cells carry the protocols' default background temperature (background_factor = 6:
-- T_0 = 6 x the free-particle active temperature T_act, docs/model.md "Vertex bath"), so f0
-- sets both; the measured 2 k_B T_c/(P sigma^3) is about 14 T_act/P in a fluid and 12 T_act/P
-- in a caged tissue, T_act ~ (f0/gamma)^2 tau_p/(3 (tau_p + tau_g)).
--   invasim sweep init protocols/sweeps/fig5_extra_curves.lua
--   invasim sweep run out/fig5_extra_curves --jobs 2
--   scripts/validation.py figure fig5 out/fig5_active out/fig5_passive out/fig5_long out/fig5_extra_curves -o docs/validation
return {
  protocol = "../invasion.lua",
  set = { system = "reduced", P = 1.3e-3,
          quench_steps = 20000, steps = 4000000, every = 16000,
          snapshot_every = 0, checkpoint_every = 100000 },
  zip = { { beta = { 1e-4, 1e-4, 1e-4, 1e-4, 1e-4, 1e-4,
                     1e-4, 1e-4, 1e-4, 1e-4, 1e-4, 1e-4,
                     1e-3, 1e-3, 1e-3, 1e-3, 1e-3, 1e-3,
                     1e-2, 1e-2, 1e-2, 1e-2, 1e-2, 1e-2 },
            tau_p = { 0.02, 0.02, 0.02, 0.02, 0.02, 0.02,
                      25.0, 25.0, 25.0, 25.0, 25.0, 25.0,
                      250.0, 250.0, 250.0, 250.0, 250.0, 250.0,
                      250.0, 250.0, 250.0, 250.0, 250.0, 250.0 },
            f0 = { 0.0051, 0.0088, 0.016, 0.028, 0.047, 0.073,
                   0.00035, 0.00061, 0.0011, 0.002, 0.0035, 0.0061,
                   0.00033, 0.00056, 0.001, 0.0018, 0.0033, 0.0056,
                   0.00033, 0.00056, 0.001, 0.0018, 0.0033, 0.0056 } } },
  seeds = { 1, 2 },
  prep = { set = { quench_steps = 0, steps = 0 } },
  -- the CI size: three points, so that the figure's code runs in CI too
  tiny = { set = { quench_steps = 100, steps = 400, every = 100, checkpoint_every = 0 },
           take = 3 },
}
