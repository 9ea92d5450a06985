-- System sizes. "paper" is the paper's standard system (docs/model.md, protocol step 1); "large" its
-- larger one; "reduced" keeps the paper's initial packing fraction (~0.01) with fewer bodies,
-- for quick runs and the default main job. L0 is the initial cubic box side; the initial x
-- ranges of the bodies scale with it (init.lua).
return {
  reduced = { N_a = 8, N_c = 400, L0 = 46.0 },
  paper = { N_a = 28, N_c = 1500, L0 = 70.0 },
  large = { N_a = 128, N_c = 7000, L0 = 116.0 },
}
