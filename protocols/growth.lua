-- A growing tumour invading a lipolytic, polydisperse adipose tissue (docs/model.md,
-- "Proliferation and death", Bodies "Lipolysis" and "Adipocytes of many sizes"): the main
-- job's chain with the paper's future directions switched on. Cancer cells divide at
-- division_rate and die at death_rate, held back by contact inhibition; the adipocytes they
-- touch shrink; the adipocytes' diameters spread log-normally. The series gains N_c (cells),
-- V0_ratio (the adipocytes' mean reference volume over the initial one) and N_touched.
--   invasim run protocols/growth.lua                    (a few minutes on 2 cores)
--   invasim run protocols/growth.lua --set division_rate=1e-3 --set steps=100000
-- The figure of docs/beyond_the_paper.md ("A growing tumour") is this run with its defaults.
local iv = require("invasim")
local parameters = require("lib.parameters")
local declare = require("lib.declare")
local stage = require("lib.stages")
local motion = require("lib.motion")
local production = require("lib.production")

-- Parameters: the shared ones (lib/parameters.lua) with this protocol's defaults for the
-- growth, the lipolysis and the adipocytes' sizes.
local note = "this protocol's default"
local p = iv.params(parameters.merge{
  division_rate = declare.engine("Proliferation", "division_rate", 3e-4, note),
  death_rate = declare.engine("Proliferation", "death_rate", 1e-4, note),
  inhibition_contacts = declare.engine("Proliferation", "inhibition_contacts", 6, note),
  lipolysis_rate = declare.engine("Lipolysis", "rate", 2e-4, note),
  lipolysis_every = declare.keyword(production.keys, "lipolysis_every", 500),
  adipocyte_spread = { 0.2, range = "[0, 1]", help = "log-normal spread of the adipocytes' diameters, mean kept (" .. note .. ")" },
  steps = declare.keyword(production.keys, "steps", 100000),
})
parameters.validate(p)
local N_a, N_c, L0 = parameters.size(p)
local clock = iv.clock()
local out = require("lib.run_dir").open(p)

-- Dilute de-mixed start, compression, quench: as in invasion.lua (the adipocytes of many sizes
-- from the start).
local tissue = stage.init(parameters.init_options(p, N_a, N_c, L0))
stage.compress(tissue, { to_phi = p.phi, ftol = p.compress_ftol, final_ftol = p.final_ftol,
                         cohesion = p.cohesive_compression, out = out, from = iv.from })
stage.quench(tissue, motion.quench_options(p, { steps = p.quench_steps }))

-- Production with proliferation and lipolysis (parameters.production_options switches them on
-- from their rates); then the report.
local result = stage.production(tissue, parameters.production_options(p, out))
require("lib.report").final(tissue, p, result, iv.clock() - clock, out)
