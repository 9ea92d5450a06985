-- The paper's Fig. 8 at reduced scale: the adipocyte packing-fraction scan
-- (protocols/packing.lua: rescale to phi_a, minimise, tether with K_ecm = 0.04 and lambda, run
-- under the pressure wall) at phi_a = 0.45 to 0.85 and lambda in {0, 0.3, 1}; beta = 1e-2,
-- tau_p = 25, f0 = 0.0024 (2 k_B T_c/(P sigma^3) = 0.37-0.39 in the paper's convention with the
-- default background, docs/model.md "Vertex bath"). Each point
-- twice: box = "pressure" (docs/model.md, protocol step 6: the left wall a piston at P after the rescale; the
-- tissue drifts back to the packing P sets) and box = "fixed" (the box keeps the rescaled
-- size, the paper's text read literally; the wall pressure is then measured). The
-- compression is shared; the rescale is per point. Two seeds. The production is 1e6 steps
-- (t = 5e4): at 2.5e5 steps, 6 of the 60 runs still drifted (docs/validation.md, "Steady state").
--   invasim sweep init protocols/sweeps/fig8_packing.lua
--   invasim sweep run out/fig8_packing --jobs 2
return {
  protocol = "../packing.lua",
  set = { system = "reduced", beta = 1e-2, tau_p = 25.0, P = 1.3e-3, f0 = 0.0024,
          K_ecm = 0.04, quench_steps = 20000, steps = 1000000, every = 2000,
          snapshot_every = 0, checkpoint_every = 20000 },
  -- descending, so that the CI size (take = 2) gets the quick ones: expanding to 0.45 takes
  -- about 6e5 FIRE steps (110 s) before the run
  product = { phi_a = { 0.85, 0.75, 0.65, 0.55, 0.45 }, lambda = { 0.0, 0.3, 1.0 },
              box = { "pressure", "fixed" } },
  seeds = { 1, 2 },
  -- the compression only (packing.lua needs one measurement to finish: 100 steps)
  prep = { set = { quench_steps = 0, steps = 100, every = 100 } },
  tiny = { set = { quench_steps = 100, steps = 400, every = 100, checkpoint_every = 0 },
           take = 2 },
}
