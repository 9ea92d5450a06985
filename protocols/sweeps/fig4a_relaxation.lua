-- The passive glass transition of the paper's Fig. 4a by its own definition: the temperature
-- below which the structural relaxation time tau_r (F_s(k = 2 pi/sigma, t) = 1/e) diverges.
-- Passive, repulsive cells (f0 = 0, beta = 0) at P = 1.3e-3 in the reduced system, six
-- temperatures 2 k_B T/(P sigma^3) = 0.03 to 0.2 (bath kT = that x P / 2) around the
-- paper's T_g ~ 0.03 and the A_n midpoints of fig4a_passive, with a correlator window of
-- 250 lags x 1000 steps = 12500 tau (the protocols' default window, 250 tau, ends before F_s
-- falls to 1/e below 2 k_B T/(P sigma^3) = 0.4), to t = 1e5 (2e6 steps). One seed, one
-- compressed tissue. About 20 minutes on one core:
--   invasim sweep init protocols/sweeps/fig4a_relaxation.lua --workspace out/fig4a_relaxation
--   invasim sweep run out/fig4a_relaxation --jobs 1 --threads 1
--   invasim sweep submit out/fig4a_relaxation --slurm --cpus-per-task 1 --time 01:00:00
return {
  protocol = "../invasion.lua",
  set = { system = "reduced", f0 = 0.0, beta = 0.0, P = 1.3e-3,
          quench_steps = 20000, steps = 2000000, every = 10000, correlate_every = 1000, lags = 250, origin_every = 5,
          snapshot_every = 0, checkpoint_every = 100000 },
  -- 2 kT/(P sigma^3) = 0.03, 0.05, 0.07, 0.1, 0.14, 0.2
  product = { kT = { 1.95e-5, 3.25e-5, 4.55e-5, 6.5e-5, 9.1e-5, 1.3e-4 } },
  seeds = { 1 },
  prep = { set = { quench_steps = 0, steps = 0 } },
  tiny = { set = { quench_steps = 100, steps = 400, every = 100, correlate_every = 20,
                   checkpoint_every = 0 }, take = 2 },
}
