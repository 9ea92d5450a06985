-- The paper's Fig. 7b at reduced scale: tethered tissue (protocols/tethered.lua) with long
-- persistence and weak cohesion, tau_p = 2500, beta = 1e-3, K_ecm in {0, 0.01, 0.04, 0.16} x
-- five f0 (2 k_B T_c/(P sigma^3) ~ 0.03 to 3 with the default background, docs/model.md
-- "Vertex bath") x two seeds, from one compressed tissue (the tethers are inserted after it, before
-- the quench). The production is 2e6 steps (t = 1e5 = 40 tau_p; the orientations decorrelate
-- about forty times): at 5e5 steps, 10 of the 40 runs still drifted (docs/validation.md,
-- "Steady state"). A_n is normalised by the K_ecm = 0 sweep, as in Fig. 7a.
--   invasim sweep init protocols/sweeps/fig7b_tethered.lua
--   invasim sweep run out/fig7b_tethered --jobs 2
--   scripts/validation.py figure fig7b out/fig7b_tethered -o docs/validation
return {
  protocol = "../tethered.lua",
  set = { system = "reduced", beta = 1e-3, tau_p = 2500.0, P = 1.3e-3,
          quench_steps = 20000, equilibrate_steps = 10000, steps = 2000000, every = 4000,
          snapshot_every = 0, checkpoint_every = 20000 },
  product = { K_ecm = { 0.0, 0.01, 0.04, 0.16 },
              f0 = { 0.00051, 0.0011, 0.0018, 0.0029, 0.0056 } },
  seeds = { 1, 2 },
  prep = { set = { quench_steps = 0, equilibrate_steps = 0, steps = 0 } },
  tiny = { set = { quench_steps = 100, equilibrate_steps = 100, steps = 400, every = 100,
                   checkpoint_every = 0 }, take = 2 },
}
