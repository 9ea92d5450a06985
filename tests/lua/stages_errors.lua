-- Test: the stage library's keyword checking. Every stage rejects an unknown key
-- (naming it, suggesting the nearest and listing the valid ones), a wrong type, a missing
-- required key and a wrong order of stages, with the caller's file and line.
package.path = "../../protocols/?.lua;" .. package.path
local iv = require("invasim")
local checks = 0

-- fn is called from a Lua closure, as a script would call it: errors carry this file's line.
local function expect_error(pattern, fn, ...)
  local args = table.pack(...)
  local ok, err = pcall(function() local r = fn(table.unpack(args, 1, args.n)); return r end)
  assert(not ok, "expected an error matching: " .. pattern)
  if not tostring(err):find(pattern) then
    error("error message\n  " .. tostring(err) .. "\ndoes not match\n  " .. pattern, 2)
  end
  checks = checks + 1
end

local init = require("lib.init")
expect_error("^stages_errors.lua:%d+: init: unknown key 'N_cc' %(did you mean 'N_c'%?%); valid keys: .*N_a, N_c",
             init, { N_cc = 10 })
expect_error("^stages_errors.lua:%d+: init: key 'N_a' must be an integer, got string", init, { N_a = "many" })
expect_error("^stages_errors.lua:%d+: init: expected a keyword table, as in init{key = value, ...}; got number", init, 5)
-- The stage checks its own declarations first (N_c is an integer), and engine errors pass
-- through the stages with their own messages (the engine's range of a cell count).
expect_error("^stages_errors.lua:%d+: init: key 'N_c' must be an integer, got 2.5", init, { N_a = 0, N_c = 2.5, L0 = 30.0 })
expect_error("cells: key 'n' = %-1 is out of range", init, { N_a = 0, N_c = -1, L0 = 30.0 })

local tissue = init{ N_a = 1, N_c = 20, L0 = 30.0 }
expect_error("compress: unknown key 'to_ph' %(did you mean 'to_phi'%?%)", require("lib.compress"), tissue, { to_ph = 0.5 })
expect_error("compress: key 'cohesion' must be a boolean %(true or false%), got string", require("lib.compress"), tissue, { cohesion = "off" })
expect_error("compress: unknown key 'beta'", require("lib.compress"), tissue, { beta = 0 })
expect_error("compress: key 'from' must be a string, got boolean", require("lib.compress"), tissue, { from = true })
-- An out that cannot hold the checkpoints is refused before the compression, not after it.
expect_error("make_dirs: cannot create directory '/proc/no_such_run/checkpoint'",
             require("lib.compress"), tissue, { to_phi = 0.5, out = "/proc/no_such_run" })
expect_error("^stages_errors.lua:%d+: production: key 'snapshot_every' must be an integer >= 0, got %-1",
             require("lib.stages").production, tissue, { snapshot_every = -1 })
expect_error("heterogeneity: missing required key 'lambda'", require("lib.heterogeneity"), tissue, {})
expect_error("heterogeneity: the tissue has no tethers; run the tether stage first",
             require("lib.heterogeneity"), tissue, { lambda = 0.3 })
expect_error("production: run the quench stage first", require("lib.production"), tissue, { steps = 10 })
expect_error("quench: key 'P' must be a number or an invasim.ramp{}, got string",
             require("lib.quench"), tissue, { P = "high" })
-- Values out of range, for stages called directly (before ranges were checked, f0 = -1 ran as athermal cells,
-- every = 0 failed with a raw "attempt to perform 'n%%0'").
expect_error("^stages_errors.lua:%d+: quench: key 'f0' = %-1 is out of range %(must be >= 0%)", require("lib.quench"), tissue, { f0 = -1 })
expect_error("^stages_errors.lua:%d+: quench: key 'kT' = %-0.5 is out of range %(must be >= 0%)", require("lib.quench"), tissue, { kT = -0.5 })
expect_error("^stages_errors.lua:%d+: production: key 'every' = 0 is out of range %(must be >= 1%)",
             require("lib.production"), tissue, { every = 0 })
expect_error("^stages_errors.lua:%d+: production: key 'correlate_every' = %-5 is out of range %(must be >= 0%)",
             require("lib.production"), tissue, { correlate_every = -5 })
-- Files asked for without a place to write them: refused, not dropped.
expect_error("^stages_errors.lua:%d+: production: snapshot_every = 5 needs out %(a run directory%)",
             require("lib.stages").production, tissue, { steps = 10, every = 5, snapshot_every = 5 })
-- An integral float passes the integer check, as every other integer key does (1e3 for 1000).
expect_error("^stages_errors.lua:%d+: production: snapshot_every = 1000 needs out %(a run directory%)",
             require("lib.stages").production, tissue, { steps = 10, every = 5, snapshot_every = 1e3 })
expect_error("^stages_errors.lua:%d+: production: key 'snapshot_every' must be an integer >= 0, got 2.5",
             require("lib.stages").production, tissue, { snapshot_every = 2.5 })
expect_error("^stages_errors.lua:%d+: production: checkpoint_every = 5 needs out %(a run directory%)",
             require("lib.production"), tissue, { steps = 10, every = 5, checkpoint_every = 5 })
expect_error("^stages_errors.lua:%d+: production: snapshot_every = 5 needs snapshots",
             require("lib.production"), tissue, { steps = 10, every = 5, snapshot_every = 5 })
-- Checked before the run, not after it (average_fraction) or when the correlator is made.
expect_error("^stages_errors.lua:%d+: production: key 'average_fraction' = 2 is out of range %(must be in %(0, 1%]%)",
             require("lib.production"), tissue, { average_fraction = 2 })
expect_error("^stages_errors.lua:%d+: production: key 'lags' = 0 is out of range %(must be >= 1%)",
             require("lib.production"), tissue, { lags = 0 })
expect_error("^stages_errors.lua:%d+: quench: vertex_bath = 'hot': unknown vertex bath; choose one of: damped, langevin",
             require("lib.quench"), tissue, { vertex_bath = "hot" })
expect_error("^stages_errors.lua:%d+: quench: vertex_kT = 0.001 sets the noise of langevin vertices, but vertex_bath = 'damped' gives them none",
             require("lib.quench"), tissue, { vertex_bath = "damped", vertex_kT = 1e-3 })
expect_error("quench: key 'vertex_gamma' must be a number, got string",
             require("lib.quench"), tissue, { vertex_gamma = "low" })
expect_error("rescale: key 'phi_a' must be a number, got boolean", require("lib.rescale"), tissue, { phi_a = true })
expect_error("tether: unknown key 'k'", require("lib.tether"), tissue, { k = 1 })
-- The production stage's column list (LAMMPS thermo style) names unknown columns.
require("lib.quench")(tissue, { steps = 10, progress = false, vertex_bath = "damped", vertex_gamma = 0.02 })
-- The Dynamics keeps the vertex bath it was made with (equilibrate cannot switch it).
expect_error("equilibrate: cannot change the vertex bath of an existing Dynamics %(Damped vertices%)",
             require("lib.quench"), tissue, { label = "equilibrate", steps = 10, vertex_bath = "langevin" })
-- The vertices' mass is the first quench's (here the default 1): a different one later is refused,
-- the same one accepted.
expect_error("^stages_errors.lua:%d+: equilibrate: vertex_mass = 4.5: the vertices' mass was set to 1 by the first quench",
             require("lib.quench"), tissue, { label = "equilibrate", steps = 10, vertex_bath = "damped", vertex_mass = 4.5 })
require("lib.quench")(tissue, { label = "equilibrate", steps = 0, progress = false, vertex_bath = "damped",
                                vertex_gamma = 0.02, vertex_mass = 1 })
assert(tissue.vertex_method:kind() == "Damped" and tissue.vertex_method:params().gamma == 0.02, "damped vertex bath")
assert(tissue.dyn:wall_state().kT == 0, "no piston noise with damped vertices")
checks = checks + 1
expect_error("production: columns%[2%] = 'A_T' is not measured; available: step, time, T_c",
             require("lib.production"), tissue, { steps = 10, every = 5, columns = { "step", "A_T" } })
local chosen = require("lib.production")(tissue, { steps = 10, every = 5, columns = { "step", "A_t", "T_c" },
                                                  progress = false, correlate_every = 0 })
assert(#chosen.series.columns == 3 and chosen.series.rows[1].A_t and chosen.summary.A_t, "chosen columns")
checks = checks + 1
-- A protocol's own columns (observers): in the series and the summary, checked like keywords.
local function mean_x(row, t)
  local sum, xs = 0, t.sys:positions(t.cells)
  for _, r in ipairs(xs) do sum = sum + r[1] end
  row.x_mean = sum / #xs
end
local own = require("lib.production")(tissue, { steps = 10, every = 5, progress = false, correlate_every = 0,
                                                observers = { { columns = { "x_mean" }, units = { x_mean = "sigma" },
                                                                sample = mean_x } } })
assert(own.series.rows[2].x_mean and own.summary.x_mean.mean and own.series.units.x_mean == "sigma",
       "an observer's column in the series and the summary")
checks = checks + 1
expect_error("^stages_errors.lua:%d+: production: observers%[1%]: missing required key 'columns' %(a table%); unknown key 'colums' %(did you mean 'columns'%?%)",
             require("lib.production"), tissue, { steps = 10, observers = { { colums = { "x" }, sample = mean_x } } })
expect_error("^stages_errors.lua:%d+: production: observers%[1%]: column 'A_t' is already measured",
             require("lib.production"), tissue, { steps = 10, observers = { { columns = { "A_t" }, sample = mean_x } } })
expect_error("^stages_errors.lua:%d+: production: observers%[1%]: columns%[1%] = x mean is not a column name",
             require("lib.production"), tissue, { steps = 10, observers = { { columns = { "x mean" }, sample = mean_x } } })
expect_error("production: observers%[1%]: sample set column 'y' to nil, not a number",
             require("lib.production"), tissue, { steps = 10, every = 5, progress = false, correlate_every = 0,
                                                  observers = { { columns = { "y" }, sample = mean_x } } })
-- An out without checkpoint/ gets one before the run (the checkpoint at the end had failed).
local bare = iv.out_dir .. "/bare_production"
for _, f in ipairs({ "/checkpoint/state.ckpt", "/checkpoint", "/series.csv" }) do os.remove(bare .. f) end
iv.make_dirs(bare)
require("lib.production")(tissue, { steps = 10, every = 5, progress = false, correlate_every = 0, out = bare })
assert(io.open(bare .. "/checkpoint/state.ckpt"), "the production's last checkpoint in a bare out")
checks = checks + 1
-- The Langevin vertex bath: vertices and piston at the background kT.
local warm = init{ N_a = 1, N_c = 20, L0 = 30.0 }
require("lib.quench")(warm, { steps = 10, progress = false, kT = 1e-3, vertex_bath = "langevin", vertex_gamma = 0.1 })
local vp = warm.vertex_method:params()
assert(warm.vertex_method:kind() == "Langevin" and vp.kT == 1e-3 and vp.gamma == 0.1, "Langevin vertex bath")
assert(warm.dyn:wall_state().kT == 1e-3, "the piston's bath is at kT")
checks = checks + 1
print("stages_errors: all " .. checks .. " checks passed")
