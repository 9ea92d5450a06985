-- fig4a_relaxation.lua run to the paper's duration, t = 5e5 (1e7 steps), with a correlator
-- window of 250 lags x 4000 steps = 5e4 tau: at the lowest temperatures F_s(t) has not
-- fallen to 1/e within that sweep's 12500 tau, and its time origins lie in the first 1e5 tau,
-- while the tissue still compacts (L_x falls by 1.4 % over the first 5e4 tau); here the
-- origins span the paper's whole run. 2 k_B T/(P sigma^3) = 0.02 to 0.2 in the reduced
-- system. About an hour on one core:
--   invasim sweep init protocols/sweeps/fig4a_relaxation_long.lua --workspace out/fig4a_relaxation_long
--   invasim sweep run out/fig4a_relaxation_long --jobs 1 --threads 1
--   invasim sweep submit out/fig4a_relaxation_long --slurm --cpus-per-task 1 --time 01:00:00
return {
  protocol = "../invasion.lua",
  set = { system = "reduced", f0 = 0.0, beta = 0.0, P = 1.3e-3,
          quench_steps = 20000, steps = 10000000, every = 10000, correlate_every = 4000, lags = 250, origin_every = 5,
          snapshot_every = 0, checkpoint_every = 100000 },
  -- 2 kT/(P sigma^3) = 0.02, 0.03, 0.05, 0.07, 0.1, 0.14, 0.2
  product = { kT = { 1.3e-5, 1.95e-5, 3.25e-5, 4.55e-5, 6.5e-5, 9.1e-5, 1.3e-4 } },
  seeds = { 1 },
  prep = { set = { quench_steps = 0, steps = 0 } },
  tiny = { set = { quench_steps = 100, steps = 400, every = 100, correlate_every = 20,
                   checkpoint_every = 0 }, take = 2 },
}
