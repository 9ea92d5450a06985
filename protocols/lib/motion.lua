-- How the cancer cells move, from the protocol's physical parameters:
--   f0 > 0            -> Active{f0, tau_p, kT} (self-propulsion, optional thermal noise)
--   f0 == 0, kT > 0   -> Langevin{kT}          (passive, thermal)
--   f0 == 0, kT == 0  -> Damped                (athermal)
-- How the adipocyte vertices (and the piston) move, from the protocol's vertex bath:
--   vertex_bath = "langevin" -> Langevin{vertex_gamma, kT}: FDT noise at the background kT
--                               (the piston gets the same bath at kT)
--   vertex_bath = "damped"   -> Damped{vertex_gamma}: no noise (driven only through contacts)
local iv = require("invasim")

local M = {}

-- The vertex baths a protocol may choose (docs/model.md, "Vertex bath": the measured table).
M.VERTEX_BATHS = { langevin = true, damped = true }

-- nil if `bath` is a vertex bath, else the reason (with the choices) to append to where the
-- value came from, e.g. "--set vertex_bath=x".
function M.check_vertex_bath(bath)
  if M.VERTEX_BATHS[bath] then return nil end
  return "unknown vertex bath; choose one of: damped, langevin"
end

-- The vertices' method for options {vertex_bath, vertex_gamma, kT}.
function M.vertex_method(group, o)
  if o.vertex_bath == "langevin" then
    return iv.Langevin{ group = group, gamma = o.vertex_gamma, kT = o.kT }
  end
  return iv.Damped{ group = group, gamma = o.vertex_gamma }
end

function M.describe_vertices(o)
  if o.vertex_bath == "langevin" then
    return string.format("Langevin vertices (gamma = %g, kT = %g)", o.vertex_gamma, o.kT)
  end
  return string.format("damped vertices (gamma = %g, no noise)", o.vertex_gamma)
end

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
