-- E_c ~ 1/P (the paper's Eq. for E_c = k_B T/(a P sigma^3), tested there at one pressure): Fig. 5's
-- beta = 1e-2, tau_p = 25 curve at reduced scale at three pressures, P = 6.5e-4, 1.3e-3 (the
-- paper's) and 2.6e-3, six self-propulsion forces each, two seeds, from one compressed
-- tissue. The forces are fig5_active.lua's scaled by sqrt(P / 1.3e-3), so that each pressure
-- spans the same 2 k_B T_c/(P sigma^3) ~ 0.01 to 3 (k_B T_c ~ f0^2). If E_c ~ 1/P, A_n
-- against 2 k_B T_c/(P sigma^3) falls on one curve for the three pressures, up to the
-- paper's a ~ (1 + c2 beta/(P sigma^3)) (c2 ~ 0.02: 1.31, 1.15, 1.08 here).
--   invasim sweep init protocols/sweeps/pressure_fig5.lua
--   invasim sweep run out/pressure_fig5 --jobs 2
--   invasim sweep analyze out/pressure_fig5 --group P
return {
  protocol = "../invasion.lua",
  set = { system = "reduced", beta = 1e-2, tau_p = 25.0,
          quench_steps = 20000, steps = 250000, every = 1000,
          snapshot_every = 0, checkpoint_every = 20000 },
  zip = { { P = { 6.5e-4, 6.5e-4, 6.5e-4, 6.5e-4, 6.5e-4, 6.5e-4,
                  1.3e-3, 1.3e-3, 1.3e-3, 1.3e-3, 1.3e-3, 1.3e-3,
                  2.6e-3, 2.6e-3, 2.6e-3, 2.6e-3, 2.6e-3, 2.6e-3 },
            f0 = { 0.00025, 0.00043, 0.00078, 0.0014, 0.0025, 0.0043,
                   0.00035, 0.00061, 0.0011, 0.002, 0.0035, 0.0061,
                   0.00049, 0.00086, 0.0016, 0.0028, 0.0049, 0.0086 } } },
  seeds = { 1, 2 },
  prep = { set = { quench_steps = 0, steps = 0 } },
  -- the CI size: three values per axis
  tiny = { set = { quench_steps = 100, steps = 400, every = 100, checkpoint_every = 0 },
           take = 3 },
}
