-- tiny.lua with a third seed: `sweep init` adds 2 points and keeps the 4 of tiny.lua.
return {
  protocol = "../../../protocols/invasion.lua",
  set = { N_a = 2, N_c = 200, background_factor = 0, quench_steps = 100, steps = 1000, every = 50,
          snapshot_every = 0, checkpoint_every = 50, correlate_every = 5 },
  product = { kT = { 1e-4, 1e-3 } },
  seeds = { 1, 2, 3 },
  prep = { set = { quench_steps = 0, steps = 0 } },
}
