-- The final summary of an invasion run, printed and (with a run directory) written to
-- summary.json: the tissue, the averages of the production run with their error bars, the
-- correlation times, shape statistics and the derived dimensionless temperature
-- k_B T_c / (P sigma^3) (the paper plots its results against the measured T_c), also in
-- the paper's convention (kT_c_paper = 2 T_c), and T_c/T_a.
local iv = require("invasim")
local log = require("lib.log")
local summary_lines = require("lib.summary")

local M = {}

local function optional(x, fmt)
  return x and string.format(fmt, x) or "not reached"
end

-- `extra` (optional): more top-level entries of summary.json (e.g. packing_scan).
function M.final(tissue, p, result, seconds, out, extra)
  local sys = tissue.sys
  local s = result.summary
  local box = sys:box()
  log.say("summary", "%d cancer cells, %d adipocytes; t = %g (%d steps); wall-clock %.1f s",
          tissue.cells:size(), sys:n_adipocytes(), sys:time(), sys:step(), seconds)
  if tissue.compression then
    log.say("summary", "compressed box L_f = %s at phi = %.4f; now L_x = %.4f, phi = %.4f",
            log.box(tissue.compression.box), tissue.compression.phi, box.lengths[1], sys:packing().total)
  end
  local n = s.T_c and s.T_c.samples or 0
  log.say("summary", "averages over the last %d of %d samples (errors from the autocorrelation time):", n, s.samples)
  summary_lines.print("summary", s, { "A_t", "A_t_max", "A_ratio", "T_c", "T_a", "T_c_over_T_a",
                                      "kT_c_paper", "P_left", "P_right",
                                      "L_x", "phi", "phi_c", "phi_a", "phi_a_local_mean", "phi_a_local_std" },
                      result.series.units)
  local derived = {}
  -- The bath temperatures the engine applied (params.json's kT is 0 for active cells, whose
  -- background is background_factor x their free-particle temperature: docs/model.md); none
  -- for a method without friction, whose noise is 0 whatever its kT.
  local function bath_kT(method)
    local params = method and method:params()
    if params and params.gamma > 0 then return params.kT end
  end
  derived.cells_kT = bath_kT(tissue.cell_method)
  derived.vertices_kT = bath_kT(tissue.vertex_method)
  if tissue.dyn and tissue.dyn:wall_state() then derived.piston_kT = tissue.dyn:wall_state().kT end
  -- Means over no sample (or NaN samples: every cell dead) are NaN: no ratios of them.
  local function finite(x) return x and x.mean == x.mean end
  if finite(s.T_c) and finite(s.T_a) and p.P > 0 then
    derived.kT_over_P = s.T_c.mean / p.P
    derived.kT_c_paper_over_P = 2 * derived.kT_over_P
    derived.T_c_over_T_a = s.T_c.mean / s.T_a.mean
    log.say("summary", "k_B T_c / (P sigma^3) = %.4g (paper's convention: %.4g), T_c / T_a = %.3g",
            derived.kT_over_P, derived.kT_c_paper_over_P, derived.T_c_over_T_a)
  end
  if s.correlation_window == 0 then  -- no production steps: no lag to decay over
    log.say("summary", "tau_d, tau_r = not measured (the correlators reached no lag)")
  elseif s.correlation_window then
    -- A time shorter than the correlator's interval (lib/production.lua) is marked.
    local function time(name)
      return optional(s[name], "%.4g") .. (s[name .. "_unresolved"] and " (unresolved)" or "")
    end
    log.say("summary", "tau_d = %s (standard normalisation %s), tau_r = %s (window %g)",
            time("tau_d"), time("tau_d_standard"), time("tau_r"), s.correlation_window)
  end
  if s.shape_3d_mean and s.shape_2d_error then
    log.say("summary", "shape parameter: 3D mean %.4f, no 2D slices (%s)", s.shape_3d_mean,
            s.shape_2d_error)
  elseif s.shape_3d_mean then
    log.say("summary", "shape parameter: 3D mean %.4f, 2D slices mean %s, median %s (%s profiles)",
            s.shape_3d_mean, optional(s.shape_2d_mean, "%.4f"), optional(s.shape_2d_median, "%.4f"),
            optional(s.shape_2d_profiles, "%d"))
  end
  if out then
    local doc = {
      averages = s, derived = derived, wall_clock_seconds = seconds, steps = sys:step(),
      time = sys:time(), box = box.lengths,
      compression = tissue.compression and { box = tissue.compression.box, phi = tissue.compression.phi,
                                             steps = tissue.compression.steps } or nil,
    }
    for k, v in pairs(extra or {}) do
      if doc[k] ~= nil then error("report: extra entry '" .. k .. "' would replace a summary entry", 2) end
      doc[k] = v
    end
    require("lib.files").write(out .. "/summary.json", iv.json_encode(doc))
    local files = {}
    for _, name in ipairs{ "series.csv", "summary.json", "correlations.csv", "shapes.csv", "snapshots/" } do
      if iv.exists(out .. "/" .. name) then files[#files + 1] = name end
    end
    log.say("summary", "results in %s (%s)", out, table.concat(files, ", "))
  end
end

return M
