-- How the cancer cells move, from the protocol's physical parameters:
--   f0 > 0            -> Active{f0, tau_p, kT} (self-propulsion, optional thermal noise)
--   f0 == 0, kT > 0   -> Langevin{kT}          (passive, thermal)
--   f0 == 0, kT == 0  -> Damped                (athermal)
-- Adipocyte vertices are always Damped (MODEL.md: driven only through contacts).
local iv = require("invasim")

local M = {}

-- The kind of method M.cell_method would make: "Active", "Langevin" or "Damped".
function M.kind(o)
  if o.f0 > 0 then return "Active" elseif o.kT > 0 then return "Langevin" end
  return "Damped"
end

function M.cell_method(group, o)
  if o.f0 > 0 then
    return iv.Active{ group = group, gamma = o.gamma, f0 = o.f0, tau_p = o.tau_p, kT = o.kT }
  elseif o.kT > 0 then
    return iv.Langevin{ group = group, gamma = o.gamma, kT = o.kT }
  end
  return iv.Damped{ group = group, gamma = o.gamma }
end

function M.describe(o)
  if o.f0 > 0 then
    return string.format("active cells (f0 = %g, tau_p = %g, kT = %g)", o.f0, o.tau_p, o.kT)
  elseif o.kT > 0 then
    return string.format("passive cells (kT = %g)", o.kT)
  end
  return "athermal cells"
end

return M
