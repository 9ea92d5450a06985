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

-- nil, or why vertex_kT cannot go with the bath: damped vertices have no noise to set.
function M.check_vertex_kT(bath, vertex_kT)
  if bath ~= "damped" or not vertex_kT or vertex_kT <= 0 then return nil end
  return string.format("vertex_kT = %g sets the noise of langevin vertices, but vertex_bath = " ..
                       "'damped' gives them none", vertex_kT)
end

-- The langevin vertices' noise temperature: vertex_kT, or the background kT when it is 0.
function M.vertex_kT(o)
  if o.vertex_kT and o.vertex_kT > 0 then return o.vertex_kT end
  return o.kT
end

-- The vertices' method for options {vertex_bath, vertex_gamma, vertex_kT, kT}.
function M.vertex_method(group, o)
  if o.vertex_bath == "langevin" then
    return iv.Langevin{ group = group, gamma = o.vertex_gamma, kT = M.vertex_kT(o) }
  end
  return iv.Damped{ group = group, gamma = o.vertex_gamma }
end

function M.describe_vertices(o, mass)
  if o.vertex_gamma == 0 then  -- Langevin or damped: no friction, no noise
    return string.format("undamped vertices (vertex_gamma = 0: no bath, mass = %g)", mass)
  end
  if o.vertex_bath == "langevin" then
    return string.format("Langevin vertices (gamma = %g, kT = %g, mass = %g)", o.vertex_gamma,
                         M.vertex_kT(o), mass)
  end
  return string.format("damped vertices (gamma = %g, mass = %g, no noise)", o.vertex_gamma, mass)
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

-- The free-particle temperature m <v^2>/3 of an active cell without noise (m = 1), as the
-- integrator makes it: (f0/gamma)^2 tau / (3 (tau + tau_g)), tau_g = m/gamma, with the
-- persistence tau of the force held over each step of dt, tau = (dt/2) (1 + rho)/(1 - rho),
-- rho = exp(-dt/tau_p) (= tau_p to 1e-6 when tau_p >> dt; dt/2 at tau_p = 0, a fresh
-- direction every step; docs/model.md, Vertex bath).
function M.active_temperature(f0, tau_p, gamma, dt)
  if f0 == 0 then return 0.0 end
  local tau_g = 1.0 / gamma
  if tau_p == math.huge then return (f0 / gamma) ^ 2 / 3 end
  local rho = math.exp(-dt / tau_p)
  local tau = 0.5 * dt * (1 + rho) / (1 - rho)
  return (f0 / gamma) ^ 2 * tau / (3 * (tau + tau_g))
end

-- The background temperature of a protocol's parameters p: for active cells with
-- background_factor > 0, that factor times their free-particle active temperature (the cells'
-- thermal noise and the langevin vertices' bath); otherwise kT.
function M.background_kT(p)
  if p.f0 > 0 and (p.background_factor or 0) > 0 then
    return p.background_factor * M.active_temperature(p.f0, p.tau_p, p.gamma, p.dt)
  end
  return p.kT
end

-- The quench options of a protocol's parameters p (the cells' motion, the vertices' bath, the
-- pressure and the time step), with `extra` (steps, label, barostat, ...) on top.
function M.quench_options(p, extra)
  local o = { P = p.P, kT = M.background_kT(p), f0 = p.f0, tau_p = p.tau_p, gamma = p.gamma, dt = p.dt,
              vertex_bath = p.vertex_bath, vertex_gamma = p.vertex_gamma,
              vertex_mass = p.vertex_mass, vertex_kT = p.vertex_kT }
  for k, v in pairs(extra or {}) do o[k] = v end
  return o
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
