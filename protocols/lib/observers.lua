-- What the production stage measures while it runs (docs/measurements.md, docs/measurements_dynamics.md). Each
-- observer has `columns` (names), `units`, and `sample(row)` that adds its values to the
-- row of the current step; the production stage calls them every `every` steps.
local iv = require("invasim")
local thermo = require("lib.thermo")

local M = {}

-- A protocol's own observer (production's `observers` key): {columns = {"x_mean", ...},
-- units = {x_mean = "sigma"}, sample = function(row, tissue) ... end}; its sample must set a
-- number for each of its columns, which then join series.csv and the summary like the others.
local custom_spec = {
  columns = { type = "table", required = true, help = "names of the columns it adds" },
  units = { type = "table", help = "unit of each column (default \"1\")" },
  sample = { type = "function", required = true, help = "function(row, tissue) setting them" },
}
-- `taken`: the columns measured already, as keys.
function M.custom(entry, owner, tissue, taken)
  local o = iv.keywords(owner, entry, custom_spec)
  if #o.columns == 0 then error(owner .. ": columns must name at least one column", 0) end
  local units = {}
  for i, c in ipairs(o.columns) do
    if type(c) ~= "string" or not c:match("^[%a_][%w_]*$") then
      error(string.format("%s: columns[%d] = %s is not a column name (letters, digits, _)", owner, i,
                          tostring(c)), 0)
    end
    if taken[c] or units[c] or c == "step" or c == "time" then
      error(string.format("%s: column '%s' is already measured", owner, c), 0)
    end
    units[c] = o.units and o.units[c] or "1"
  end
  return {
    columns = o.columns, units = units,
    sample = function(row)
      o.sample(row, tissue)
      for _, c in ipairs(o.columns) do
        if type(row[c]) ~= "number" then
          error(string.format("%s: sample set column '%s' to %s, not a number", owner, c,
                              tostring(row[c])), 0)
        end
      end
    end,
  }
end

-- Temperatures, wall pressures, box length, packing fractions (lib/thermo.lua).
function M.thermo(tissue)
  return {
    columns = thermo.columns_of(tissue), units = thermo.units,
    sample = function(row)
      for k, v in pairs(thermo.sample(tissue)) do row[k] = v end
    end,
  }
end

-- Interfacial area from the Voronoi tessellation of cells and vertices: A_t, A_t^max, their
-- ratio, the mean of the local adipocyte packing fraction and its spread Delta phi_a, and the
-- adipocytes' area on the walls (A_wall_a, left out of A_t^max's S_i: docs/measurements.md).
function M.interface(tissue, radical)
  local sys = tissue.sys
  return {
    columns = { "A_t", "A_t_max", "A_ratio", "phi_a_local_mean", "phi_a_local_std", "A_wall_a" },
    units = { A_t = "sigma^2", A_t_max = "sigma^2", A_ratio = "1", phi_a_local_mean = "1",
              phi_a_local_std = "1", A_wall_a = "sigma^2" },
    sample = function(row)
      local v = sys:voronoi{ radical = radical }
      row.A_t, row.A_t_max, row.A_ratio = v.A_t, v.A_t_max, v.A_ratio
      row.phi_a_local_mean, row.phi_a_local_std = v.phi_a_local_mean, v.phi_a_local_std
      row.A_wall_a = v.adipocyte_wall
    end,
  }
end

-- Lipolysis (docs/model.md, Bodies, "Lipolysis"): the adipocytes' mean reference volume as a
-- fraction of their initial one, and how many of them cancer cells touch now.
function M.lipolysis(tissue, lipolysis)
  local sys = tissue.sys
  return {
    columns = { "V0_ratio", "N_touched" },
    units = { V0_ratio = "1", N_touched = "adipocytes" },
    sample = function(row)
      local sum, n = 0.0, 0
      for _, a in ipairs(sys:adipocytes()) do
        sum, n = sum + a.ref_volume / a.ref_volume_initial, n + 1
      end
      local touched = 0
      for _, t in ipairs(lipolysis:touched(sys)) do if t then touched = touched + 1 end end
      row.V0_ratio, row.N_touched = n > 0 and sum / n or 1.0, touched
    end,
  }
end

-- Proliferation (docs/model.md, "Proliferation and death"): follow_cells makes the tissue's
-- groups again after cells divided or died (a group keeps the indices of its time; the
-- production stage calls it before the observers sample), and the observer gives N_c.
function M.follow_cells(tissue)
  tissue.cells = tissue.sys:group("cancer")
  if tissue.vertices then tissue.vertices = tissue.sys:group("vertices") end
end

function M.proliferation(tissue)
  return {
    columns = { "N_c" }, units = { N_c = "cells" },
    sample = function(row) row.N_c = tissue.cells:size() end,
  }
end

-- Energy of each force term (one extra force evaluation per sample; the trajectory is not
-- changed: sys:compute() restores the forces the Dynamics keeps).
function M.energy(tissue)
  local columns, units = { "E_total" }, { E_total = "eps_c" }
  for name in pairs(tissue.sys:compute()) do
    if name ~= "total" and name ~= "virial" then
      columns[#columns + 1] = "E_" .. name
      units["E_" .. name] = "eps_c"
    end
  end
  table.sort(columns, function(a, b) return a == "E_total" or (b ~= "E_total" and a < b) end)
  return {
    columns = columns, units = units,
    sample = function(row)
      for name, e in pairs(tissue.sys:compute()) do
        if name ~= "virial" then row["E_" .. name] = e end
      end
    end,
  }
end

return M
