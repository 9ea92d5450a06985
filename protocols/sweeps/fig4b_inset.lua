-- The inset of the paper's Fig. 4b: de-mixed against mixed start at beta = 1e-2, tau_p = 25 and
-- f0 = 0.0019 (2 k_B T_c/(P sigma^3) ~ 0.3 in the paper's convention with the default
-- background, docs/model.md "Vertex bath", where the paper reports a
-- steady A_n ~ 0.55 from both starts), three seeds each. `start` changes the initial placement,
-- so every point compresses its own tissue (no shared preparation). Production t = 75000
-- (three times fig4b_cohesive.lua's): at t = 25000 the two starts were still 0.29 and 0.64
-- apart, so the inset's question (do they meet?) needs the longer runs.
--   invasim sweep init protocols/sweeps/fig4b_inset.lua
--   invasim sweep run out/fig4b_inset --jobs 2
return {
  protocol = "../invasion.lua",
  set = { system = "reduced", beta = 1e-2, tau_p = 25.0, P = 1.3e-3, f0 = 0.0019,
          quench_steps = 20000, steps = 1500000, every = 2000,
          snapshot_every = 0, checkpoint_every = 20000 },
  product = { start = { "demixed", "mixed" } },
  seeds = { 1, 2, 3 },
  tiny = { set = { quench_steps = 100, steps = 400, every = 100, checkpoint_every = 0 },
           take = 2 },
}
