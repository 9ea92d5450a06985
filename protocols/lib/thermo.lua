-- Thermodynamic columns of a tissue, measured from the engine (docs/measurements_dynamics.md, "Thermo columns"):
-- temperatures of the cells and the vertices (equipartition kT = m <v^2> / 3), their ratio
-- T_c/T_a, the cells' temperature in the paper's convention (kT_c_paper = (2m/3N) sum v^2 =
-- 2 T_c, the axis of its figures), the pressure
-- each wall feels (|x force of the sites on it| / (L_y L_z)), the box length L_x, packing
-- fractions, and (optionally) the energy of every force term.
local M = {}

M.columns = { "step", "time", "T_c", "T_a", "T_c_over_T_a", "kT_c_paper", "P_left", "P_right", "L_x", "phi", "phi_c", "phi_a" }
M.units = { step = "1", time = "tau", T_c = "eps_c", T_a = "eps_c", T_c_over_T_a = "1",
            kT_c_paper = "eps_c", P_left = "eps_c/sigma^3",
            P_right = "eps_c/sigma^3", L_x = "sigma", phi = "1", phi_c = "1", phi_a = "1" }

-- The columns of a tissue: without walls (a fully periodic box, protocols/cells_only.lua)
-- no wall pressures, without adipocyte vertices no T_a.
function M.columns_of(tissue)
  local columns = {}
  for _, c in ipairs(M.columns) do
    local wall = c == "P_left" or c == "P_right"
    if not (wall and not tissue.walls) and not ((c == "T_a" or c == "T_c_over_T_a") and not tissue.vertices) then
      columns[#columns + 1] = c
    end
  end
  return columns
end

-- One row {name = value} for the current state.
function M.sample(tissue)
  local sys = tissue.sys
  local box = sys:box()
  local area = box.lengths[2] * box.lengths[3]
  local phi = sys:packing()
  local T_c = sys:temperature(tissue.cells)
  local row = {
    step = sys:step(), time = sys:time(), T_c = T_c, kT_c_paper = 2 * T_c,
    L_x = box.lengths[1], phi = phi.total, phi_c = phi.cancer, phi_a = phi.adipocyte,
  }
  if tissue.vertices then
    row.T_a = sys:temperature(tissue.vertices)
    row.T_c_over_T_a = row.T_a > 0 and T_c / row.T_a or 0 / 0
  end
  if tissue.walls then
    local left, right = tissue.walls:reaction()
    row.P_left, row.P_right = math.abs(left) / area, math.abs(right) / area
  end
  return row
end

return M
