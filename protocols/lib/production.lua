-- Stage "production" (docs/model.md, protocol step 7): runs the tissue's Dynamics (made by quench) for
-- `steps` steps with observers attached and returns the series and a summary: time averages
-- over the last `average_fraction` of the run with error bars (src/measure/mean_error.hpp), the
-- correlation times and shape statistics. The run is an invasim.Simulation (src/run/) whose
-- operations each have their own schedule, at the System's steps that are multiples of their
-- interval (so with quench_steps = 1500 and every = 1000 the first row is at step 2000, 500
-- steps in), called in this order at a step where several are due:
--   every `correlate_every` steps: the cancer cells' correlators (C_vv, <n.n>, MSD, F_s)
--   every `every` steps:           thermo columns, A_t (Voronoi) if `interface`, energies if
--                                  `energy`; one row of the series (series.csv in `out`)
--   every `snapshot_every` steps:  a frame of `snapshots` (an invasim.Snapshots), if given
--   every `checkpoint_every` steps and on SIGINT/SIGTERM: out/checkpoint/state.ckpt
-- With `proliferation`, cells divide and die every `proliferation_every` steps, before all of
-- these; the series gains N_c, and the correlators follow the cells present at the start (a
-- cell that dies leaves them; daughters, without a time origin, do not join).
--   at the end:                    tau_d, tau_r, 3D shape parameters and random slices
--
--   local result = require("lib.production")(tissue, { steps = 1e5, every = 1000, out = dir })
local iv = require("invasim")
local log = require("lib.log")
local observers = require("lib.observers")
local series_file = require("lib.series")
local resume = require("lib.resume")

local spec = {
  steps = { 100000, range = "[0, inf)", help = "production steps" },
  every = { 1000, range = "[1, inf)", help = "steps between measurements (a row of series.csv)" },
  interface = true,          -- Voronoi interfacial area every `every` steps
  radical = false,           -- radical (power) tessellation instead of the paper's Voronoi
  energy = false,            -- energy of each force term every `every` steps
  columns = { type = "table" },    -- the series' columns, LAMMPS thermo style: {"step", "A_t", ...}
                               -- (default: every column of the observers switched on)
  -- The correlators' defaults: samples 0.5 tau apart (dt = 0.05) resolve C_vv's 1/e time
  -- (tau_d ~ 0.9 tau in the invasion runs; samples 1 tau apart put it 3 % low), a window of
  -- 500 lags (250 tau) and an origin every 10 tau (the cost of 25 live origins per sample).
  correlate_every = { 10, range = "[0, inf)", help = "steps between correlator samples (0: none)" },
  lags = { 500, range = "[1, inf)", help = "correlator lags: C_vv, F_s, ... at 0 .. lags - 1 samples (window lags x correlate_every steps)" },
  origin_every = { 20, range = "[1, inf)", help = "correlator samples between two time origins" },
  slices_per_body = { 20, type = "number", range = "[0, inf)" },  -- random slices per adipocyte at the end (0: none)
  average_fraction = { 0.5, range = "(0, 1]" },  -- the summary averages the last half of the samples
  out = { type = "string" },        -- directory for series.csv, correlations.csv, shapes.csv
  checkpoint_every = { 0, range = "[0, inf)", help = "steps between checkpoints in out/checkpoint/ (0: only on SIGINT/SIGTERM); also one at the last step" },
  lipolysis = { type = "Lipolysis", help = "adipocytes shrinking where cancer cells touch them (off: nil)" },
  lipolysis_every = { 1000, range = "[1, inf)", help = "steps between two applications of lipolysis (each recomputes the touched adipocytes' V_i, ~2 ms each)" },
  proliferation = { type = "Proliferation", help = "cancer cells dividing and dying (off: nil); the correlators follow the cells present at the start, the dead leaving them" },
  proliferation_every = { 100, range = "[1, inf)", help = "steps between two applications of proliferation" },
  snapshots = { type = "Snapshots" },  -- an invasim.Snapshots writing a frame every snapshot_every steps
  snapshot_every = { 0, range = "[0, inf)" },  -- steps between snapshots (0: none)
  progress = true,
  label = "production",
  on_sample = { type = "function" },   -- function(row, tissue) called after each sample
  -- The protocol's own columns (lib/observers.lua, custom); they join series.csv, the summary
  -- and sweep collect.
  observers = { type = "table", help = "own columns: {{columns = {...}, units = {...}, sample = function(row, tissue)}}" },
}

local function summarise(rows, columns, fraction)
  local summary = {}
  for _, c in ipairs(columns) do
    if c ~= "step" and c ~= "time" then
      local xs = {}
      for i, row in ipairs(rows) do xs[i] = row[c] end
      if #xs > 0 then
        local m = iv.mean_error(xs, { fraction = fraction })
        -- error from the integrated autocorrelation time tau_int (in samples); error_converged:
        -- Sokal's window criterion met; false when the window is too short for the column's
        -- correlation time, and `error` (and tau_int) are then lower bounds.
        summary[c] = { mean = m.mean, error = m.error, samples = m.n, tau_int = m.tau_int,
                       error_converged = m.resolved }
      end
    end
  end
  return summary
end

-- End-of-run shape statistics: 3D shape parameter per adipocyte, slice histogram. A slice the
-- 2D analysis cannot read (a crumpled mesh whose cross-section has holes without an outer
-- boundary) leaves the 2D statistics out, with the reason as shape_2d_error and in the log,
-- instead of losing the run's summary after its whole production.
local function shapes(sys, per_body, label)
  local s3 = sys:shape_parameters()
  local mean3 = 0
  for _, a in ipairs(s3) do mean3 = mean3 + a / #s3 end
  local result = { shape_3d = s3, shape_3d_mean = mean3 }
  if per_body > 0 and #s3 > 0 then
    local ok, a2 = pcall(sys.slices, sys, { per_body = per_body })
    if not ok then
      result.shape_2d_error = tostring(a2)
      log.say(label, "warning: no 2D shape statistics: %s", result.shape_2d_error)
      return result
    end
    local mean2 = 0
    for _, a in ipairs(a2) do mean2 = mean2 + a / #a2 end
    result.shape_2d_mean = mean2
    -- The median as well: a plane grazing a fold of a wrinkled body (A_0 > 1) cuts off a
    -- sliver region whose p^2/(4 pi s) runs into the hundreds, and a few of them dominate the
    -- mean; the median is the robust location of the distribution.
    if #a2 > 0 then
      local sorted = {}
      for i, a in ipairs(a2) do sorted[i] = a end
      table.sort(sorted)
      local h = #sorted // 2
      result.shape_2d_median = #sorted % 2 == 1 and sorted[h + 1] or 0.5 * (sorted[h] + sorted[h + 1])
    end
    result.shape_2d_profiles = #a2
    result.shape_2d_histogram = iv.histogram(a2, { lo = 1.0, hi = 1.5, bins = 25 })
  end
  return result
end

-- A decay time read at a lag averaged over fewer time origins than this is logged as such.
local min_origins = 10

-- The stage: production(tissue, opts); production.keys is its keyword spec (lib/declare.lua
-- declares protocol parameters from it).
local function production(tissue, opts)
  local o = iv.keywords(opts and opts.label or "production", opts, spec)
  if o.snapshot_every > 0 and not o.snapshots then
    error(string.format("%s: snapshot_every = %d needs snapshots (an invasim.Snapshots)", o.label,
                        o.snapshot_every), 2)
  end
  if o.checkpoint_every > 0 and not o.out then
    error(string.format("%s: checkpoint_every = %d needs out (a run directory)", o.label,
                        o.checkpoint_every), 2)
  end
  if not tissue.dyn then error(o.label .. ": run the quench stage first (it makes the Dynamics)", 2) end
  local sys, dyn = tissue.sys, tissue.dyn
  local active = { observers.thermo(tissue) }
  if o.proliferation then active[#active + 1] = observers.proliferation(tissue) end
  if o.interface and sys:n_adipocytes() > 0 then active[#active + 1] = observers.interface(tissue, o.radical) end
  if o.energy then active[#active + 1] = observers.energy(tissue) end
  if o.lipolysis then active[#active + 1] = observers.lipolysis(tissue, o.lipolysis) end
  local columns, units = {}, {}
  local function add_columns(ob)
    for _, c in ipairs(ob.columns) do columns[#columns + 1] = c; units[c] = ob.units[c] end
  end
  for _, ob in ipairs(active) do add_columns(ob) end
  -- The protocol's own, after the others (their names must be new: `units` holds those taken).
  for i, entry in ipairs(o.observers or {}) do
    local ok, custom = pcall(observers.custom, entry, string.format("%s: observers[%d]", o.label, i),
                             tissue, units)
    if not ok then error(custom, 2) end
    active[#active + 1] = custom
    add_columns(custom)
  end
  if o.columns then
    local chosen = {}
    for i, c in ipairs(o.columns) do
      if not units[c] and c ~= "step" and c ~= "time" then
        local names = {}
        for _, name in ipairs(columns) do names[#names + 1] = name end
        error(string.format("%s: columns[%d] = '%s' is not measured; available: %s (energies with energy = true)",
                            o.label, i, tostring(c), table.concat(names, ", ")), 2)
      end
      chosen[i] = c
    end
    columns = chosen
  end
  local correlator
  if o.correlate_every > 0 then
    correlator = iv.Correlator{ group = tissue.cells, interval = o.correlate_every * dyn:dt(),
                                lags = o.lags, origin_every = o.origin_every }
  end
  -- The contacts too: a protocol may change them as it runs (on_sample), and a resumed run
  -- continues with the checkpoint's.
  local parts = { system = sys, dynamics = dyn, tethers = tissue.tethers, correlator = correlator,
                  contacts = tissue.contacts }
  local checkpoint = o.out and resume.checkpoint_path(o.out) or nil
  -- Its directory made (or refused) now, not when the first checkpoint is due.
  if checkpoint then iv.make_dirs(o.out .. "/checkpoint") end
  if o.steps > math.maxinteger - sys:step() then  -- the step counter is a 64-bit integer
    error(string.format("%s: steps = %d from step %d overflows the step counter (at most %d)",
                        o.label, o.steps, sys:step(), math.maxinteger), 2)
  end
  local rows, end_step = {}, sys:step() + o.steps
  if resume.pending() and checkpoint then
    local state = resume.deserialize(iv.load_checkpoint(checkpoint, parts), checkpoint)
    rows, end_step, tissue.compression = state.rows, state.end_step, state.compression
    tissue.last_checkpoint = { path = checkpoint, step = sys:step() }  -- good until replaced
    resume.done()
    if o.proliferation then observers.follow_cells(tissue) end
    -- Frames after the checkpoint's step belong to the abandoned part of the run: out of the
    -- ParaView indexes until they are written again.
    if o.snapshots then o.snapshots:forget_after(sys:step()) end
    log.say(o.label, "resumed at step %d (t = %g) from %s; %d steps to go", sys:step(), sys:time(),
            checkpoint, end_step - sys:step())
  end
  local file = o.out and series_file.open(o.out .. "/series.csv", columns, units, rows) or nil
  local rows_text = resume.growing_list(rows)  -- each row serialized once, at its first checkpoint
  local sim = iv.Simulation{ system = sys, dynamics = dyn }
  -- Proliferation and lipolysis first: at a step where they are due, the samples and the
  -- checkpoint see their result. Their time starts with the production's (a resumed run's too).
  local start = end_step - o.steps
  if o.proliferation then
    sim:proliferation(o.proliferation, { every = o.proliferation_every, since = start })
  end
  if o.lipolysis then sim:lipolysis(o.lipolysis, { every = o.lipolysis_every, since = start }) end
  if correlator then sim:sample(correlator, { every = o.correlate_every }) end
  sim:observe(function()
    if o.proliferation then observers.follow_cells(tissue) end  -- before any observer reads them
    local row = {}
    for _, ob in ipairs(active) do ob.sample(row) end
    rows[#rows + 1] = row
    if file then file:write(row) end
    if o.on_sample then o.on_sample(row, tissue) end
  end, { every = o.every })
  if o.snapshots and o.snapshot_every > 0 then sim:snapshots(o.snapshots, { every = o.snapshot_every }) end
  if checkpoint then
    -- The checkpoint (stamped with the run's identity), noted in log.txt once written.
    sim:checkpoint(resume.stamp{
      path = checkpoint, tethers = tissue.tethers, correlator = correlator, contacts = tissue.contacts,
      extra = function()
        return resume.serialize{ rows = rows_text(), end_step = end_step, compression = tissue.compression }
      end,
      written = function(step)
        tissue.last_checkpoint = { path = checkpoint, step = step }
        log.note(o.label, "checkpoint of step %d written to %s", step, checkpoint)
      end,
      -- at_end: a run ends on a checkpoint of its last step, so a run stopped and resumed
      -- ends with the same state.ckpt as one never interrupted.
      every = o.checkpoint_every > 0 and o.checkpoint_every or nil, on_stop = true, at_end = true,
    })
  end
  local n = end_step - sys:step()
  local progress = o.progress and iv.Progress{ total = n, label = o.label } or nil
  local clock = iv.clock()
  local ok, err = pcall(sim.run, sim, n, { progress = progress })
  if file then file:close() end
  if o.proliferation then observers.follow_cells(tissue) end
  if not ok then
    local last = tissue.last_checkpoint
    local where = last and string.format("; last good checkpoint: %s (step %d)", last.path, last.step)
                  or (checkpoint and "; no checkpoint was written by this run" or "")
    error(tostring(err) .. where, 0)
  end
  local signal = iv.interrupted()
  if signal and sys:step() >= end_step then
    -- The signal came with the last steps: the production is complete, and the run finishes
    -- (its summary takes moments) instead of asking for a resume with nothing to run.
    log.say(o.label, "%s arrived as the last step completed: finishing the run", signal)
  elseif signal then
    if progress then progress:stop() end
    if checkpoint then
      error(string.format("stopped by %s at step %d (t = %g); checkpoint saved to %s; continue with: %s",
                          signal, sys:step(), sys:time(), checkpoint,
                          resume.continue_command(o.out)), 0)
    end
    error(string.format("stopped by %s at step %d (t = %g); no run directory, nothing saved", signal,
                        sys:step(), sys:time()), 0)
  end
  if progress then progress:finish() end

  local summary = summarise(rows, columns, o.average_fraction)
  summary.samples = #rows
  summary.seconds = iv.clock() - clock
  if correlator then
    summary.tau_d = correlator:tau_d()
    summary.tau_d_standard = correlator:tau_d_standard()
    summary.tau_r = correlator:tau_r()
    local interval, unresolved, few = o.correlate_every * dyn:dt(), {}, {}
    local result = correlator:result()
    local lag_t, origins = result.columns.t, result.columns.origins
    -- The longest lag the run reached (a run shorter than lags x interval stops before it).
    summary.correlation_window = lag_t[#lag_t] or 0
    -- A decay time below the first lag is a straight line from C(0) = 1 to C(interval): not
    -- resolved (its bias depends on C's shape between the samples; a few % at tau_d ~ 0.9
    -- interval). Flagged in summary.json and the log. Each time also records the time origins
    -- averaged at the lag where the function crossed 1/e: one near the end of a short run
    -- rests on a few.
    for _, name in ipairs{ "tau_d", "tau_d_standard", "tau_r" } do
      local tau = summary[name]
      if tau and tau <= interval then
        summary[name .. "_unresolved"] = true
        unresolved[#unresolved + 1] = string.format("%s = %.4g", name, tau)
      end
      for k = 1, tau and #lag_t or 0 do
        if lag_t[k] >= tau then
          summary[name .. "_origins"] = origins[k]
          if origins[k] < min_origins then
            few[#few + 1] = string.format("%s = %.4g (%d)", name, tau, origins[k])
          end
          break
        end
      end
    end
    if #unresolved > 0 then
      log.say(o.label, "warning: %s below the correlator's interval %g (correlate_every = %d steps): " ..
              "not resolved by its samples; set a smaller correlate_every",
              table.concat(unresolved, ", "), interval, o.correlate_every)
    end
    if #few > 0 then
      log.say(o.label, "warning: %s from fewer than %d time origins at their lag: a longer run, " ..
              "or a smaller origin_every", table.concat(few, ", "), min_origins)
    end
    if o.out then
      require("lib.files").write(o.out .. "/correlations.csv", series_file.columns_text(result))
    end
  end
  local shape = shapes(sys, o.slices_per_body, o.label)
  summary.shape_3d_mean = shape.shape_3d_mean
  summary.shape_3d = shape.shape_3d   -- per adipocyte, at the end of the run
  summary.shape_2d_mean = shape.shape_2d_mean
  summary.shape_2d_median = shape.shape_2d_median
  summary.shape_2d_profiles = shape.shape_2d_profiles
  summary.shape_2d_error = shape.shape_2d_error
  if o.out and shape.shape_2d_histogram then
    local h = shape.shape_2d_histogram
    local lines = { "A2_lo,A2_hi,count,density" }
    for i = 1, #h.counts do
      lines[#lines + 1] = string.format("%.6g,%.6g,%d,%.8g", h.edges[i], h.edges[i + 1], h.counts[i], h.density[i])
    end
    require("lib.files").write(o.out .. "/shapes.csv", table.concat(lines, "\n") .. "\n")
  end
  return { series = { columns = columns, units = units, rows = rows }, summary = summary,
           correlator = correlator, shape = shape }
end

return setmetatable({ keys = spec }, { __call = function(_, tissue, opts) return production(tissue, opts) end })
