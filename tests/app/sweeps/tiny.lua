-- A tiny sweep for the tests: 2 temperatures x 2 seeds of the reduced invasion protocol with
-- 2 adipocytes and 200 cells (fewer would squeeze each adipocyte against its own periodic
-- image), all starting from one shared preparation (compression only).
return {
  protocol = "../../../protocols/invasion.lua",
  set = { N_a = 2, N_c = 200, background_factor = 0, quench_steps = 100, steps = 1000, every = 50,
          snapshot_every = 0, checkpoint_every = 50, correlate_every = 5 },
  product = { kT = { 1e-4, 1e-3 } },
  seeds = { 1, 2 },
  prep = { set = { quench_steps = 0, steps = 0 } },
}
