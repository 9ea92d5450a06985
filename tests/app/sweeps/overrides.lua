-- A spec with a CI size for the tests of sweep init --tiny / --set / --take: 3 kT x 2 f0 x
-- a zip of 3 (tau_p, beta) pairs x 2 seeds, with a shared preparation that sets its own steps.
return {
  protocol = "../../../protocols/invasion.lua",
  set = { N_a = 2, N_c = 200, background_factor = 0, quench_steps = 100, steps = 1000, every = 50 },
  product = { kT = { 1e-4, 1e-3, 1e-2 }, f0 = { 0.0, 0.01 } },
  zip = { { tau_p = { 25.0, 250.0, 2500.0 }, beta = { 0.0, 1e-3, 1e-2 } } },
  seeds = { 1, 2 },
  prep = { set = { quench_steps = 0, steps = 0 } },
  tiny = { set = { quench_steps = 10, steps = 200, every = 100, N_c = 20 }, take = 2 },
}
