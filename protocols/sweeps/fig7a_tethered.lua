-- The paper's Fig. 7a at reduced scale: tethered tissue (protocols/tethered.lua) at tau_p = 25,
-- beta = 1e-2, K_ecm in {0, 0.01, 0.04, 0.16} x five f0 (2 k_B T_c/(P sigma^3) ~ 0.03 to 3 with
-- the default background, docs/model.md "Vertex bath") x two
-- seeds, from one compressed tissue (the tethers are inserted after it, before the quench).
-- A_n is normalised by the K_ecm = 0 sweep (its plateau below 1 with tethers). The production is
-- 1e6 steps (t = 5e4, a tenth of the paper's 5e5): at 2.5e5 steps, 6 of the 40 runs still drifted
-- (docs/validation.md, "Steady state").
--   invasim sweep init protocols/sweeps/fig7a_tethered.lua
--   invasim sweep run out/fig7a_tethered --jobs 2
return {
  protocol = "../tethered.lua",
  set = { system = "reduced", beta = 1e-2, tau_p = 25.0, P = 1.3e-3,
          quench_steps = 20000, equilibrate_steps = 10000, steps = 1000000, every = 2000,
          snapshot_every = 0, checkpoint_every = 20000 },
  product = { K_ecm = { 0.0, 0.01, 0.04, 0.16 },
              f0 = { 0.00058, 0.0012, 0.002, 0.0033, 0.0062 } },
  seeds = { 1, 2 },
  prep = { set = { quench_steps = 0, equilibrate_steps = 0, steps = 0 } },
  tiny = { set = { quench_steps = 100, equilibrate_steps = 100, steps = 400, every = 100,
                   checkpoint_every = 0 }, take = 2 },
}
