-- The paper's Fig. 3 at reduced scale: passive, repulsive cancer cells (f0 = 0, beta = 0) at the
-- five temperatures of the figure, k_B T/(P sigma^3) = 1.25e-3, 7.89e-2, 0.125, 0.198, 1.25 in
-- the paper's convention (twice the equipartition T_c, docs/model.md "Equations of motion"), so
-- the bath is kT = that x P / 2 (P = 1.3e-3), one run each from one compressed tissue: A_t(t) over the run and
-- slices of the last snapshot (docs/validation.md, scripts/validation.py figure fig3).
--   invasim sweep init protocols/sweeps/fig3_passive_slices.lua
--   invasim sweep run out/fig3_passive_slices --jobs 2
--   scripts/validation.py figure fig3 out/fig3_passive_slices -o docs/validation
return {
  protocol = "../invasion.lua",
  set = { system = "reduced", f0 = 0.0, beta = 0.0, P = 1.3e-3,
          quench_steps = 20000, steps = 400000, every = 2000,
          snapshot_every = 100000, checkpoint_every = 20000 },
  product = { kT = { 8.125e-7, 5.1285e-5, 8.125e-5, 1.287e-4, 8.125e-4 } },
  seeds = { 1 },
  prep = { set = { quench_steps = 0, steps = 0 } },
  -- the CI size (invasim sweep init --tiny): two temperatures, a few hundred steps
  tiny = { set = { quench_steps = 100, steps = 400, every = 100, snapshot_every = 400,
                   checkpoint_every = 0 }, take = 2 },
}
