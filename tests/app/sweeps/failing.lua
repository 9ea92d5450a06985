-- One of the two points fails when it runs (beta = 0.5 is not below alpha = 0.2, which the
-- protocol checks at run time), the other succeeds: the sweep must finish the good one.
return {
  protocol = "../../../protocols/invasion.lua",
  set = { N_a = 2, N_c = 200, quench_steps = 50, steps = 100, every = 50, snapshot_every = 0,
          checkpoint_every = 0, correlate_every = 0 },
  product = { beta = { 0.01, 0.5 } },
}
