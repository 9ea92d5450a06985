-- tiny.lua's sweep over f0 instead of kT: another sweep, which `sweep init` must refuse to add
-- to tiny.lua's workspace (tests/app/sweep_workspace.sh).
return {
  protocol = "../../../protocols/invasion.lua",
  set = { N_a = 2, N_c = 200, background_factor = 0, quench_steps = 100, steps = 1000, every = 50,
          snapshot_every = 0, checkpoint_every = 50, correlate_every = 5 },
  product = { f0 = { 0.0, 0.01 } },
  seeds = { 1, 2 },
  prep = { set = { quench_steps = 0, steps = 0 } },
}
