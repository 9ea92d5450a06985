-- A sweep whose shared preparation fails at run time (beta = 0.5 is not below alpha = 0.2):
-- under Slurm its dependent array must be cancelled and its points returned to pending
-- (tests/app/sweep_slurm.sh), not left waiting for a dependency that can never be satisfied.
return {
  protocol = "../../../protocols/invasion.lua",
  set = { N_a = 2, N_c = 200, quench_steps = 50, steps = 100, every = 50, snapshot_every = 0,
          checkpoint_every = 0, correlate_every = 0 },
  product = { kT = { 1e-4, 1e-3 } },
  seeds = { 1 },
  prep = { set = { quench_steps = 0, steps = 0, beta = 0.5 } },
}
