-- FIRE's largest time step for a tissue (docs/model.md, "Protocols": the compression and the
-- packing scan's minimisation).
local iv = require("invasim")

local M = {}

-- FIRE's largest time step for this tissue, used by every minimisation of a tissue with
-- adipocytes (lib.compress, lib.rescale). The adipocytes' volume term (eps_v) gives each mesh
-- a stiff breathing mode: at eps_v = 1e3 and unit vertex mass semi-implicit Euler becomes
-- unstable in it between dt = 0.2 and 0.25. With the engine's dt_max = 0.5, FIRE grew dt into
-- that instability, reset, and grew it again, over and over: the reduced system took 114160
-- iterations, the paper's 484720 (375000 of them in the final FIRE); with 0.15, 22840 and
-- 45944 (docs/performance.md, "Compression"). The mode's frequency grows as
-- sqrt(eps_v), so the step shrinks as 1/sqrt(eps_v); it never exceeds 0.15 (softer meshes leave the contacts'
-- own limit, not measured beyond that). Without adipocytes (or eps_v = 0): the engine's.
-- A mesh of radius r has its mode's stiffness per vertex ~ eps_v (dV/dx)^2 / V^2 ~ eps_v / r^2:
-- with adipocytes of many sizes (init's diameter_spread) the smallest sets the step, which
-- scales with its radius relative to the median body's, (V_min / V_median)^(1/3).
function M.dt_max(tissue)
  local eps_v = tissue.shape and tissue.shape:params().eps_v or 0
  if tissue.sys:n_adipocytes() == 0 or eps_v <= 0 then return iv.Fire.defaults.dt_max end
  local dt = 0.15 * math.sqrt(math.min(1.0, 1e3 / eps_v))
  if tissue.params and (tissue.params.diameter_spread or 0) > 0 then
    local v = {}
    for _, a in ipairs(tissue.sys:adipocytes()) do v[#v + 1] = a.ref_volume end
    table.sort(v)
    dt = dt * math.min(1.0, (v[1] / v[(#v + 1) // 2]) ^ (1 / 3))
  end
  return dt
end

return M
