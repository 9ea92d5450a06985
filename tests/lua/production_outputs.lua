-- Test: the production stage's observers write the run directory: series.csv
-- (header with units, one row per `every` steps, A_t within [0, A_t^max]), correlations.csv
-- (C_vv(0) = F_s(0) = 1), shapes.csv, summary.json, params.json, log.txt and snapshots;
-- series.csv and the summary report T_c/T_a and kT_c_paper (= 2 T_c, the paper's convention);
-- the summary averages the last half of the rows; P_left and P_right are the walls' reactions
-- over the wall area at each sample; the piston shares the langevin vertices' bath (CTest runs
-- it at kT = 1e-4).
package.path = "../../protocols/?.lua;" .. package.path
local iv = require("invasim")
local parameters = require("lib.parameters")
local stage = require("lib.stages")
local p = iv.params(parameters.merge{})
local N_a, N_c, L0 = parameters.size(p)
local out = require("lib.run_dir").open(p)
local tissue = stage.init{ N_a = N_a, N_c = N_c, L0 = L0, seed = p.seed, start = p.start,
                           shape_param = p.A_0, eps_v = p.eps_v, eps_a = p.eps_a,
                           alpha = p.alpha, beta = p.beta }
stage.compress(tissue, { to_phi = p.phi, ftol = p.compress_ftol, final_ftol = p.final_ftol })
stage.quench(tissue, { P = p.P, kT = p.kT, f0 = p.f0, tau_p = p.tau_p, gamma = p.gamma,
                       vertex_bath = p.vertex_bath, vertex_gamma = p.vertex_gamma, dt = p.dt,
                       steps = p.quench_steps })
-- The piston shares the vertices' bath (langevin vertices: noise at the cells' kT).
assert(p.vertex_bath == "langevin" and p.kT > 0 and tissue.dyn:wall_state().kT == p.kT,
       string.format("the piston's kT = %g, the bath's %g", tissue.dyn:wall_state().kT, p.kT))
-- Each sample's wall pressures against the walls' reactions over the wall area at that moment.
local pressures_checked = 0
local function check_pressures(row, t)
  local left, right = t.walls:reaction()
  local box = t.sys:box()
  local area = box.lengths[2] * box.lengths[3]
  for name, force in pairs{ P_left = left, P_right = right } do
    local want = math.abs(force) / area
    assert(want > 0 and math.abs(row[name] - want) <= 1e-12 * want,
           string.format("%s %.10g, reaction / area %.10g", name, row[name], want))
  end
  pressures_checked = pressures_checked + 1
end
local result = stage.production(tissue, { steps = p.steps, every = p.every,
                                          correlate_every = p.correlate_every,
                                          snapshot_every = p.snapshot_every,
                                          checkpoint_every = p.checkpoint_every, out = out,
                                          on_sample = check_pressures })
require("lib.report").final(tissue, p, result, 0, out)

local function lines(path)
  local t = {}
  for line in assert(io.open(path)):lines() do t[#t + 1] = line end
  return t
end
local function split(line)
  local t = {}
  for field in (line .. ","):gmatch("([^,]*),") do t[#t + 1] = field end
  return t
end

local series = lines(out .. "/series.csv")
local header = split(series[1])
assert(series[1]:find("^step,time %[tau%],T_c %[eps_c%],T_a %[eps_c%],T_c_over_T_a,kT_c_paper %[eps_c%],P_left %[eps_c/sigma%^3%]"), series[1])
assert(series[1]:find("A_t %[sigma%^2%],A_t_max %[sigma%^2%],A_ratio"), series[1])
local expected_rows = p.steps // p.every
assert(#series == expected_rows + 1, "series.csv has " .. (#series - 1) .. " rows, expected " .. expected_rows)
local col = {}
for j, h in ipairs(header) do col[h:match("^(%S+)")] = j end
for i = 2, #series do
  local f = split(series[i])
  local A_t, A_max = tonumber(f[col.A_t]), tonumber(f[col.A_t_max])
  assert(A_t > 0 and A_t <= A_max, "A_t out of range in row " .. i)
  -- T_c/T_a and the paper's temperature convention (2 T_c) are derived from the same row.
  -- Each of the three numbers is printed with 10 digits (%.10g, a relative rounding of up to
  -- 5e-10 each), hence 2e-9.
  local T_c, T_a = tonumber(f[col.T_c]), tonumber(f[col.T_a])
  assert(math.abs(tonumber(f[col.T_c_over_T_a]) - T_c / T_a) <= 2e-9 * T_c / T_a, "T_c_over_T_a in row " .. i)
  assert(math.abs(tonumber(f[col.kT_c_paper]) - 2 * T_c) <= 2e-9 * T_c, "kT_c_paper in row " .. i)
  -- Samples are taken at the steps of the System that are multiples of `every`.
  local step = tonumber(f[col.step])
  assert(step % p.every == 0 and step > tissue.sys:step() - p.steps and step <= tissue.sys:step(),
         "step column: " .. step)
  if i > 2 then assert(step == tonumber(split(series[i - 1])[col.step]) + p.every, "step spacing") end
end
local corr = lines(out .. "/correlations.csv")
assert(corr[1] == "t,origins,cvv,cvv_std,vv,nn,msd,alpha2,fs", corr[1])
local c0 = split(corr[2])
assert(tonumber(c0[3]) == 1 and tonumber(c0[9]) == 1, "C_vv(0) and F_s(0) must be 1: " .. corr[2])
assert(lines(out .. "/shapes.csv")[1] == "A2_lo,A2_hi,count,density")
local summary = table.concat(lines(out .. "/summary.json"), "\n")
assert(summary:find('"A_t": {') and summary:find('"wall_clock_seconds"'), "summary.json")
assert(summary:find('"T_c_over_T_a": {') and summary:find('"kT_c_paper": {') and
       summary:find('"kT_c_paper_over_P": '), "summary.json: T_c/T_a and the paper's kT_c")
-- The derived numbers from the averages: k_B T_c/(P sigma^3), the paper's 2 T_c/P, T_c/T_a.
local s = iv.read_json(out .. "/summary.json")
local T_c, T_a, d = s.averages.T_c.mean, s.averages.T_a.mean, s.derived
assert(T_c > 0 and T_a > 0, "summary.json: T_c, T_a")
assert(math.abs(d.kT_over_P - T_c / p.P) <= 1e-12 * d.kT_over_P, "derived.kT_over_P")
assert(math.abs(d.kT_c_paper_over_P - 2 * T_c / p.P) <= 1e-12 * d.kT_c_paper_over_P,
       "derived.kT_c_paper_over_P = 2 T_c/P")
assert(math.abs(d.T_c_over_T_a - T_c / T_a) <= 1e-12 * d.T_c_over_T_a, "derived.T_c_over_T_a")
-- The bath temperatures applied: the quench above gave the cells, the vertices and the piston
-- the same kT.
assert(d.cells_kT == p.kT and d.vertices_kT == p.kT and d.piston_kT == p.kT,
       string.format("derived bath temperatures %s, %s, %s; kT = %g", tostring(d.cells_kT),
                     tostring(d.vertices_kT), tostring(d.piston_kT), p.kT))
-- The averages are over the last half of the rows (floor(n/2): the window of
-- scripts/invasim_analysis/steady.py too), as series.csv holds them (%.10g).
local rows = {}
for i = 2, #series do rows[#rows + 1] = split(series[i]) end
local half = #rows // 2
for _, name in ipairs{ "A_t", "T_c", "P_right", "L_x" } do
  local sum = 0
  for i = #rows - half + 1, #rows do sum = sum + tonumber(rows[i][col[name]]) end
  local a = s.averages[name]
  assert(a.samples == half and math.abs(a.mean - sum / half) <= 1e-9 * math.abs(a.mean),
         string.format("summary %s: mean %.10g over %d samples, series' last %d rows %.10g", name,
                       a.mean, a.samples, half, sum / half))
end
assert(pressures_checked == expected_rows, "wall pressures checked at " .. pressures_checked .. " samples")
-- Each error bar is the standard error from the integrated autocorrelation time, summed up to
-- Sokal's window (the smallest W >= 5 tau_int(W), W <= (2n/3 - 1)/2, the subtracted mean's
-- bias corrected by 1/(1 - (2W + 1)/n); docs/measurements_dynamics.md, "Summary"), and says
-- whether the window criterion was met (error_converged), here computed anew over
-- series.csv's window; a lower bound is marked "(*)" in the printed summary. Runs of at
-- least 256 rows must show both kinds (the CTest run of 1000 rows does).
local function autocorrelation_error(xs)
  local n, mean = #xs, 0
  for _, x in ipairs(xs) do mean = mean + x / n end
  local function gamma(t)
    local s = 0
    for i = 1, n - t do s = s + (xs[i] - mean) * (xs[i + t] - mean) end
    return s / n
  end
  local g0 = gamma(0)
  if g0 <= 0 then return 0, true, 0.5 end
  local w_max = math.min(n - 1, math.max(0, math.floor((2 / 3 * n - 1) / 2)))
  local tau, window, met = 0.5, 0, false
  for w = 1, w_max do
    tau, window = tau + gamma(w) / g0, w
    if w >= 5 * tau then met = true break end
  end
  local c_f = 2 * tau * g0 / (1 - (2 * window + 1) / n)
  local variance = g0 + c_f / n
  if c_f < variance then variance, c_f = g0 / (1 - 1 / n), g0 / (1 - 1 / n) end
  return math.sqrt(c_f / n), met, c_f / (2 * variance), window - 5 * tau
end
local converged, judged = 0, 0
for name, a in pairs(s.averages) do
  if type(a) == "table" and a.error and col[name] then
    assert(type(a.error_converged) == "boolean", "summary " .. name .. ": error_converged missing")
    local xs = {}
    for i = #rows - half + 1, #rows do xs[#xs + 1] = tonumber(rows[i][col[name]]) end
    local err, met, tau, margin = autocorrelation_error(xs)
    if math.abs(margin) > 1e-3 then  -- series.csv's %.10g could flip a tie
      assert(a.error_converged == met, string.format("summary %s: error_converged = %s, " ..
             "Sokal's criterion over series.csv says %s", name, a.error_converged, met))
      assert(math.abs(a.error - err) <= 1e-6 * err + 1e-300 and math.abs(a.tau_int - tau) <= 1e-6 * tau,
             string.format("summary %s: error %.10g, tau_int %.10g; over series.csv %.10g, %.10g",
                           name, a.error, a.tau_int, err, tau))
    end
    judged = judged + 1
    if a.error_converged then converged = converged + 1 end
  end
end
assert(judged >= 10, "error_converged judged for " .. judged .. " averages")
if #rows >= 256 then
  assert(converged > 0 and converged < judged, string.format("%d of %d error bars converged: " ..
         "expected both kinds at %d rows", converged, judged, #rows))
end
-- The slices' median A_2D (robust to sliver profiles) next to the mean, and the profile count.
local median = tonumber(summary:match('"shape_2d_median": ([%d%.eE+-]+)'))
local profiles = tonumber(summary:match('"shape_2d_profiles": (%d+)'))
local mean2 = tonumber(summary:match('"shape_2d_mean": ([%d%.eE+-]+)'))
assert(median and median >= 1.0 and profiles and profiles > 0 and mean2,
       "summary.json: shape_2d_median and shape_2d_profiles")
local log_text = table.concat(lines(out .. "/log.txt"), "\n")
assert(log_text:find("summary: T_c_over_T_a = ") and log_text:find("summary: kT_c_paper = ") and
       log_text:find("paper's convention: "), "the printed summary shows T_c/T_a and kT_c_paper")
for _, name in ipairs{ "A_t", "T_c", "T_a", "P_left", "L_x", "phi" } do
  local line = log_text:match("\nsummary: " .. name .. " +=[^\n]*")
  assert(line, "printed summary line of " .. name)
  assert((line:find("%(%*%)$") ~= nil) == (s.averages[name].error_converged == false),
         "the printed line marks a lower bound iff error_converged is false: " .. line)
end
assert(converged == judged or log_text:find("%(%*%) error bar a lower bound"), "the (*) footnote")
assert(table.concat(lines(out .. "/params.json"), "\n"):find('"N_c": 60'), "params.json")
assert(table.concat(lines(out .. "/log.txt"), "\n"):find("summary: results in"), "log.txt")
local pvd = table.concat(lines(out .. "/snapshots/adipocytes.pvd"), "\n")
local frames = 0
for _ in pvd:gmatch("<DataSet ") do frames = frames + 1 end
assert(frames == 1 + p.steps // p.snapshot_every, "adipocytes.pvd has " .. frames .. " frames")
print("production_outputs: ok (" .. expected_rows .. " rows, " .. frames .. " frames, " .. converged ..
      " of " .. judged .. " error bars converged)")
