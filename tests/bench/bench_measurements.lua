-- Cost of the main job's measurements relative to its dynamics (docs/performance.md, target 3), at the
-- main job's cadence (protocols/invasion.lua defaults; --set changes them as there):
--   thermo columns and the Voronoi measurement (A_t) every `every` steps, the cells'
--   correlators every `correlate_every` steps, and at the end of the run the 3D shape
--   parameters and `slices_per_body` random slices per adipocyte (amortised over `steps`).
-- The tissue is built as the main job builds it (init, compress, quench); the correlator is
-- warmed up over one window (lags x correlate_every steps) so that all its time origins are
-- active, then `blocks` blocks of `every` steps are timed, each piece with os.clock (CPU time
-- of the process: with --threads 1 a loaded machine does not distort the split).
--   build/invasim run tests/bench/bench_measurements.lua --threads 1 [--set system=paper]
local here = debug.getinfo(1, "S").source:match("^@(.*/)") or "./"
package.path = here .. "../../protocols/?.lua;" .. package.path
local iv = require("invasim")
local parameters = require("lib.parameters")
local stage = require("lib.stages")
local thermo = require("lib.thermo")

local production_keys = require("lib.production").keys  -- the production stage's defaults
local p = iv.params(parameters.merge{
  blocks = { 5, type = "integer", range = "[1, inf)", help = "blocks of `every` steps timed" },
  lags = { production_keys.lags[1], type = "integer", range = "[1, inf)", help = "correlator lags" },
  origin_every = { production_keys.origin_every[1], type = "integer", range = "[1, inf)",
                   help = "a time origin every this many correlator samples" },
})
parameters.validate(p)
local N_a, N_c, L0 = parameters.size(p)
local tissue = stage.init(parameters.init_options(p, N_a, N_c, L0))
stage.compress(tissue, { to_phi = p.phi, ftol = p.compress_ftol, final_ftol = p.final_ftol,
                         cohesion = p.cohesive_compression, progress = false })
stage.quench(tissue, require("lib.motion").quench_options(p, { steps = p.quench_steps }))
local sys, dyn = tissue.sys, tissue.dyn
local lags, origin_every = p.lags, p.origin_every
local corr = p.correlate_every > 0 and iv.Correlator{ group = tissue.cells,
  interval = p.correlate_every * dyn:dt(), lags = lags, origin_every = origin_every } or nil
local chunk = p.correlate_every > 0 and p.correlate_every or p.every
if p.every % chunk ~= 0 then error("bench: every must be a multiple of correlate_every", 0) end

local t = { dynamics = 0, correlators = 0, thermo = 0, voronoi = 0, slices = 0 }
local function timed(key, f, ...)
  local c0 = os.clock()
  f(...)
  t[key] = t[key] + os.clock() - c0
end
-- Warm-up: one correlator window (untimed).
if corr then
  for _ = 1, lags do
    dyn:run(sys, p.correlate_every)
    corr:sample(sys)
  end
end
for _ = 1, p.blocks do
  for _ = 1, p.every // chunk do
    timed("dynamics", dyn.run, dyn, sys, chunk)
    if corr then timed("correlators", corr.sample, corr, sys) end
  end
  timed("thermo", thermo.sample, tissue)
  if sys:n_adipocytes() > 0 then timed("voronoi", sys.voronoi, sys, {}) end
end
-- End of the run (lib/production.lua, shapes): once per `steps` steps.
timed("slices", function()
  sys:shape_parameters()
  if sys:n_adipocytes() > 0 then sys:slices{ per_body = 20 } end
end)

local steps = p.blocks * p.every
local per = {  -- CPU seconds per `every` steps
  dynamics = t.dynamics / p.blocks, correlators = t.correlators / p.blocks,
  thermo = t.thermo / p.blocks, voronoi = t.voronoi / p.blocks,
  slices = p.steps > 0 and t.slices * p.every / p.steps or 0,
}
local total = per.dynamics + per.correlators + per.thermo + per.voronoi + per.slices
print(string.format("bench_measurements: %d sites, %d timed steps, every = %d, correlate_every = %d, steps = %d",
                    sys:n_sites(), steps, p.every, p.correlate_every, p.steps))
print(string.format("CPU seconds per %d steps (share of a production run):", p.every))
for _, k in ipairs{ "dynamics", "correlators", "voronoi", "thermo", "slices" } do
  print(string.format("  %-12s %9.4f s  %6.2f %%", k, per[k], 100 * per[k] / total))
end
print(string.format("  %-12s %9.4f s  %6.2f %%  (one slice pass: %.3f s, amortised over %d steps)",
                    "measurements", total - per.dynamics, 100 * (total - per.dynamics) / total,
                    t.slices, p.steps))
print(string.format("site-steps per CPU second of the dynamics: %.3e", sys:n_sites() * steps / t.dynamics))
