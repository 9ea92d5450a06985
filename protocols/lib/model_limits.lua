-- The limits of the model beyond each parameter's own range: values that iv.params accepts
-- (they lie in the declared ranges) but that make a run meaningless, overflow a derived
-- quantity or never end. check(p, N_a, N_c, L0) refuses them before anything runs or any file
-- is written, with a message naming the parameter, its value and what goes wrong. The bounds
-- and where they come from (docs/model.md; docs/reliability.md, "Values in range that mean
-- nothing, stalled minimisations and sweep workspaces"):
--   P, kT, f0 <= 0.1   the contact springs F = (eps/s)(1 - r/s) have a modulus of eps_c/sigma^3
--                      (energy eps_c, force eps_c/sigma): a pressure, a temperature or a
--                      self-propulsion force of order 1 overlaps the bodies by a diameter;
--                      the paper's values are at most ~1e-2;
--   dt                 velocity Verlet is stable for omega dt < 2: the stiffest contact
--                      (s = 0.9, omega^2 = eps/(m s^2)) gives dt < 1.8, the adipocytes' volume
--                      mode dt < 0.25 sqrt(1e3 / eps_v) (docs/model.md, "Compression": unstable
--                      above 0.2-0.25 at eps_v = 1e3), a tether dt < 2 sqrt(21 / K_ecm) (two
--                      adipocytes of 42 unit-mass vertices), the vertices' modes scaled by
--                      sqrt(vertex_mass) (M.max_dt); and dt >= 1e-9: a smaller step moves a
--                      body at the model's speeds (~1e-2 sigma/tau) by less than 1e3 rounding
--                      units of its position, and the temperatures come out as 0/0;
--   gamma, vertex_gamma  gamma dt / (2 m) <= 0.5 (m = 1 for the cells, vertex_mass for the
--                      vertices): the integrator's half-step velocities are hotter by
--                      1 / (1 - gamma dt / (2 m)), which diverges at 1;
--   tau_p              0 (a fresh orientation every step) or exp(-dt / tau_p) >= 1e-20: a
--                      smaller tau_p is tau_p = 0 in all but its rounding;
--   A_0 <= 3           the paper's 1.0-1.3; a cube has 1.38; the reference area grows as
--                      A_0^(2/3) and its energy overflows long before A_0 = 1e308;
--   L0                 the initial packing fraction >= 1e-6: the compression from it to phi
--                      takes ln(phi / phi_0) / ln(1 + step) steps, each a FIRE minimisation;
--   every <= steps     (when steps > 0) a longer interval leaves series.csv without a row;
--                      snapshot_every, checkpoint_every and correlate_every larger than steps
--                      mean "none in this run" (a sweep may fix them while its points vary
--                      steps; the start's frame is still written);
--   lipolysis_every, proliferation_every <= steps  (when their rates are > 0) they apply at
--                      the multiples of the interval within the production: a longer one
--                      applies once, for part of the run, or never;
--   mean_degree <= N_a - 1  (tethered protocols) all pairs tethered;
--   compress_ftol, final_ftol  at least 10 rounding units of the forces: the residual force
--                      of a minimised tissue cannot go below eps (2.2e-16) x the box side x
--                      the stiffest spring (64 eps_v / 1e3 for the volume mode, 1/0.81 for a
--                      contact), and a FIRE asked for less runs to its iteration limit (1 adipocyte
--                      and 20 cells compressed to a box of 5.3: 1e-13 reached, 1e-14 not in
--                      2e5 iterations, stuck at 1.7e-14; eps x 5.3 x 64 = 7.5e-14). The bound
--                      takes the initial box L0, larger than the compressed one: a margin.
local iv = require("invasim")

local M = {}

M.max_load = 0.1          -- P, kT, f0 in eps_c units (the contact modulus is 1)
M.min_dt = 1e-9           -- tau
M.max_damping = 0.5       -- gamma dt / (2 m)
M.min_orientation_correlation = 1e-20  -- exp(-dt / tau_p) over one step
M.max_A_0 = 3.0
M.min_initial_phi = 1e-6
M.ftol_rounding_units = 10

local function fail(fmt, ...) error(string.format(fmt, ...), 0) end

-- The largest stable time step of velocity Verlet in the tissue's stiffest mode, and that
-- mode: a contact spring between cells (2 / omega with omega^2 = eps_c / (m s^2), s = 0.9,
-- m = 1), one between a vertex of mass vertex_mass (default 1) and a cell (s = 1.45) or
-- another vertex (s = 2), or the adipocytes' volume mode (0.25 sqrt(1e3 / eps_v) for unit-mass
-- vertices); a vertex's modes scale with sqrt(vertex_mass).
function M.max_dt(eps_v, vertex_mass)
  local m = vertex_mass or 1
  local vertex = m ~= 1 and string.format(", vertex_mass = %g", m) or ""  -- in a vertex mode
  local modes = { { 2 * 0.9, "a contact spring between cells of diameter 0.9" },
                  { 2 * 1.45 * math.sqrt(math.min(m, 1)), "a contact spring between a cell and a vertex" .. vertex },
                  { 2 * 2 * math.sqrt(m), "a contact spring between two vertices" .. vertex } }
  if eps_v > 0 then
    modes[#modes + 1] = { 0.25 * math.sqrt(1e3 / eps_v) * math.sqrt(m),
                          string.format("the adipocytes' volume mode at eps_v = %g", eps_v) .. vertex }
  end
  local limit, mode = math.huge, nil
  for _, x in ipairs(modes) do if x[1] < limit then limit, mode = x[1], x[2] end end
  return limit, mode
end

-- The smallest force tolerance a minimisation can reach in a box of side L (see above).
function M.min_ftol(eps_v, L)
  local stiffest = math.max(1 / 0.81, 64 * eps_v / 1e3)
  return M.ftol_rounding_units * 2.220446049250313e-16 * L * stiffest
end

-- The bodies' volume (sigma^3) of N_a adipocytes (outer diameter 6) and N_c cells (0.9 / 1.1).
local function body_volume(N_a, N_c)
  return N_a * math.pi / 6 * 6 ^ 3 + N_c * math.pi / 6 * (0.9 ^ 3 + 1.1 ^ 3) / 2
end

local function check_loads(p)
  -- What each is, and the overlap it causes in diameters (a spring of stiffness eps/s^2: P s^2
  -- and f0 press it by P s^3 / eps and f0 s / eps, kT by sqrt(kT / eps) s).
  local what = { P = "the pressure on the left wall (eps_c/sigma^3)",
                 kT = "the thermal energy (eps_c)", f0 = "the self-propulsion force (eps_c/sigma)",
                 vertex_kT = "the vertices' thermal energy (eps_c)" }
  local overlap = { P = function(v) return v end, kT = math.sqrt, f0 = function(v) return v end,
                    vertex_kT = math.sqrt }
  for _, key in ipairs{ "P", "kT", "f0", "vertex_kT" } do
    local v = p[key]
    if v and v > M.max_load then
      fail("%s = %g: %s is not small against the contacts' modulus eps_c = 1: the bodies would " ..
           "overlap by about %.3g of a diameter; %s must be at most %g (the paper's values are " ..
           "at most ~1e-2)", key, v, what[key], overlap[key](v), key, M.max_load)
    end
  end
  -- The active cells' background (background_factor x their free-particle temperature).
  local factor = p.background_factor or 0
  if (p.f0 or 0) > 0 and factor > 0 and (p.gamma or 0) > 0 then
    local T0 = require("lib.motion").background_kT(p)
    if T0 > M.max_load then
      fail("background_factor = %g with f0 = %g, tau_p = %g: the background temperature %g " ..
           "(eps_c) is not small against the contacts' modulus eps_c = 1; it must be at most %g " ..
           "(lower f0 or background_factor)", factor, p.f0, p.tau_p, T0, M.max_load)
    end
  end
end

local function check_time_step(p)
  local dt = p.dt
  if not dt then return end
  if dt < M.min_dt then
    fail("dt = %g: a step this short moves a body at the model's speeds (~1e-2 sigma/tau) by " ..
         "less than 1e3 rounding units of its position (the temperatures would be 0/0); dt must " ..
         "be at least %g", dt, M.min_dt)
  end
  local limit, mode = M.max_dt(p.eps_v or 0, p.vertex_mass)
  -- A tether of stiffness K_ecm between two adipocytes of 42 vertices (reduced mass
  -- 21 vertex_mass): omega^2 = K_ecm / (21 vertex_mass).
  local reduced = 21 * (p.vertex_mass or 1)
  if p.K_ecm and p.K_ecm > 0 and 2 * math.sqrt(reduced / p.K_ecm) < limit then
    limit = 2 * math.sqrt(reduced / p.K_ecm)
    mode = string.format("a tether at K_ecm = %g", p.K_ecm)
  end
  if dt >= limit then
    fail("dt = %g: velocity Verlet is unstable in the stiffest mode (%s) above dt = %.3g; the " ..
         "first steps would blow up", dt, mode, limit)
  end
  -- The cells have unit mass, the vertices vertex_mass.
  for _, key in ipairs{ "gamma", "vertex_gamma" } do
    local g, m = p[key], key == "vertex_gamma" and p.vertex_mass or 1
    if g and g * dt / (2 * m) > M.max_damping then
      fail("%s = %g with dt = %g and m = %g: gamma dt / (2 m) = %.3g must be at most %g (the " ..
           "integrator's half-step velocities are hotter by 1 / (1 - gamma dt / (2 m)), which " ..
           "diverges at 1); %s must be at most %.3g", key, g, dt, m, g * dt / (2 * m),
           M.max_damping, key, 2 * M.max_damping * m / dt)
    end
  end
  local tau_p = p.tau_p
  if tau_p and tau_p > 0 and math.exp(-dt / tau_p) < M.min_orientation_correlation then
    fail("tau_p = %g with dt = %g: the orientation keeps exp(-dt/tau_p) = %.3g of its direction " ..
         "over one step, nothing a double can tell from tau_p = 0 (a fresh orientation every " ..
         "step); set tau_p = 0 or at least %.3g", tau_p, dt, math.exp(-dt / tau_p),
         dt / -math.log(M.min_orientation_correlation))
  end
end

local function check_box(p, N_a, N_c, L0)
  local volume = body_volume(N_a, N_c)
  local phi0 = volume / L0 ^ 3
  if phi0 < M.min_initial_phi then
    local step = iv.compress.defaults.step
    local phi = p.phi or 0.72
    fail("L0 = %g: the initial packing fraction would be %.3g (%d adipocytes and %d cells, " ..
         "%.4g sigma^3, in a box of %.3g sigma^3): compressing it to phi = %g in steps of %g " ..
         "takes %.3g steps; L0 must be at most %.4g (an initial packing fraction of %g)",
         L0, phi0, N_a, N_c, volume, L0 ^ 3, phi, step, math.log(phi / phi0) / math.log(1 + step),
         (volume / M.min_initial_phi) ^ (1 / 3), M.min_initial_phi)
  end
end

local function check_intervals(p)
  if not (p.steps and p.steps > 0) then return end
  if p.every and p.every > p.steps then
    fail("every = %d is larger than steps = %d: series.csv would have no row; set every to at " ..
         "most %d", p.every, p.steps, p.steps)
  end
  local applied = { lipolysis = (p.lipolysis_rate or 0) > 0,
                    proliferation = (p.division_rate or 0) > 0 or (p.death_rate or 0) > 0 }
  for _, what in ipairs{ "lipolysis", "proliferation" } do
    local every = p[what .. "_every"]
    if applied[what] and every and every > p.steps then
      fail("%s_every = %d is larger than steps = %d: %s applies at the multiples of %d within " ..
           "the production, once for part of it or never; set %s_every to at most %d", what,
           every, p.steps, what, every, what, p.steps)
    end
  end
end

-- The tethered protocols' network: the closest pairs of adipocytes, mean_degree per adipocyte.
local function check_tethers(p, N_a)
  if p.mean_degree and p.mean_degree > N_a - 1 then
    fail("mean_degree = %g is more than %d, the degree of every adipocyte when all %d are " ..
         "tethered to each other; set mean_degree to at most %d", p.mean_degree, N_a - 1, N_a,
         N_a - 1)
  end
end

local function check_tolerances(p, L0)
  local floor = M.min_ftol(p.eps_v or 0, L0)
  for _, key in ipairs{ "compress_ftol", "final_ftol" } do
    local v = p[key]
    if v and v < floor then
      fail("%s = %g: below %d rounding units of the forces in this tissue (eps x L0 x the " ..
           "stiffest spring = %.3g): a FIRE asked for less may never converge and would run to " ..
           "its iteration limit in every minimisation; %s must be at least %.3g", key, v,
           M.ftol_rounding_units, floor / M.ftol_rounding_units, key, floor)
    end
  end
end

-- The parameters as a plain table: iv.params' table refuses to read an undeclared name, and a
-- protocol declares only some of those checked here (K_ecm: tethered.lua, packing.lua).
local function plain(params)
  local p = {}
  for k, v in pairs(params) do p[k] = v end
  return p
end

-- Refuses the dynamics' parameters (P, kT, f0, dt, gamma, vertex_gamma, tau_p, K_ecm; those
-- the protocol declares) that make a run meaningless: for protocols without adipocytes too
-- (cells_only.lua).
function M.check_dynamics(params)
  local p = plain(params)
  check_loads(p)
  check_time_step(p)
end

-- Refuses the parameters (with the resolved system size) that make the run meaningless.
function M.check(params, N_a, N_c, L0)
  local p = plain(params)
  M.check_dynamics(p)
  if p.A_0 and p.A_0 > M.max_A_0 then
    fail("A_0 = %g: the adipocytes' reference shape parameter must be at most %g (the paper's " ..
         "values are 1.0-1.3, a cube has 1.38; the reference face areas grow as A_0^(2/3))",
         p.A_0, M.max_A_0)
  end
  check_box(p, N_a, N_c, L0)
  check_intervals(p)
  check_tethers(p, N_a)
  check_tolerances(p, L0)
end

return M
