-- The main job: cancer cells invading adipose tissue (docs/model.md, protocol steps 1, 2, 3, 7).
-- Results go to the run directory (--out DIR, default out/invasion): params.json, log.txt,
-- series.csv, summary.json, correlations.csv, shapes.csv, snapshots/.
--
-- Defaults: the "reduced" system (8 adipocytes, 400 cancer cells), active cells with
-- tau_p = 25 and cohesion beta = 1e-2 at P = 1.3e-3; about 15 seconds on 2 cores.
-- The paper's standard system is one --set away:
--   invasim run protocols/invasion.lua --set system=paper
-- (--set system=large for 128 adipocytes and 7000 cells; --set steps=... for longer runs.)
-- How to write a protocol like this one: docs/protocols.md.
local iv = require("invasim")
local parameters = require("lib.parameters")
local stage = require("lib.stages")
local motion = require("lib.motion")

-- Parameters: declared with their ranges in lib/parameters.lua; --set changes them.
local p = iv.params(parameters.declarations())
parameters.validate(p)
local N_a, N_c, L0 = parameters.size(p)  -- the system preset, unless N_a, N_c, L0 are set
local clock = iv.clock()

-- The run directory: params.json, resume.txt (for --resume), log.txt.
local out = require("lib.run_dir").open(p)

-- Initial configuration: dilute and de-mixed, cancer cells left of the adipocytes, in a
-- cubic box of side L0 with walls in x and periodic y and z.
local tissue = stage.init(parameters.init_options(p, N_a, N_c, L0))

-- Athermal isotropic compression to the packing fraction phi in steps of 3 %, each followed
-- by FIRE, with the cells' cohesion off (or the compressed tissue of --from).
stage.compress(tissue, { to_phi = p.phi, ftol = p.compress_ftol, final_ftol = p.final_ftol,
                         cohesion = p.cohesive_compression, out = out, from = iv.from })

-- Quench: the left wall becomes a piston at pressure P; the cells become active (f0, tau_p)
-- or thermal (kT), the adipocyte vertices get their bath.
stage.quench(tissue, motion.quench_options(p, { steps = p.quench_steps }))

-- Production: A_t (Voronoi), temperatures and wall pressures every `every` steps, the cells'
-- correlators, shapes at the end; snapshots and checkpoints into the run directory.
local result = stage.production(tissue, parameters.production_options(p, out))

-- Report: averages with error bars, printed and written to summary.json.
require("lib.report").final(tissue, p, result, iv.clock() - clock, out)
