-- The main job: cancer cells invading adipose tissue (docs/model.md, protocol steps 1, 2, 3, 7).
-- init (dilute, de-mixed) -> compress to phi -> quench (left wall to pressure P, cells
-- active or thermal) -> production with measurements (A_t from the Voronoi tessellation,
-- temperatures, wall pressures, correlators, shapes), then a summary. Results go to the run
-- directory (--out DIR, default out/invasion): params.json, log.txt, series.csv,
-- summary.json, correlations.csv, shapes.csv, snapshots/.
--
-- Defaults: the "reduced" system (8 adipocytes, 400 cancer cells), active cells with
-- tau_p = 25 and cohesion beta = 1e-2 at P = 1.3e-3; about a minute on 2 cores.
-- The paper's standard system is one --set away:
--   invasim run protocols/invasion.lua --set system=paper
-- (--set system=large for 128 adipocytes and 7000 cells; --set steps=... for longer runs.)
local iv = require("invasim")
local protocol = require("lib.protocol")

local p = iv.params(protocol.declarations())

protocol.validate(p)
local clock = iv.clock()
local out = require("lib.run_dir").open(p)
local tissue = protocol.prepare(p, out)
local result = protocol.produce(tissue, p, out)
require("lib.report").final(tissue, p, result, iv.clock() - clock, out)
