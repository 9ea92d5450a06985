-- The parameters of the tissue protocols (invasion.lua, tethered.lua, packing.lua,
-- bath_cell.lua), declared in this one place so that the protocols agree: each with its
-- default, range, unit and meaning (`invasim params protocols/invasion.lua` lists them). A
-- protocol adds its own with merge{...}; size(p) resolves the system preset; validate(p)
-- checks the combinations of parameters before anything runs.
local iv = require("invasim")
local declare = require("lib.declare")
local presets = require("lib.presets")
local production = require("lib.production")

local M = {}

-- The preset names, the allowed values of `system`.
local function preset_names()
  local names = {}
  for k in pairs(presets) do names[#names + 1] = k end
  table.sort(names)
  return names
end

-- The common parameter declarations (merged into a protocol's iv.params{} table). Each number
-- carries its allowed range (interval notation, checked with the --set values when the
-- protocol calls iv.params, before anything runs); 0 means "from the preset" for N_a, N_c, L0
-- and "off" for the *_every intervals.
function M.declarations()
  return {
    system = { "reduced", choices = preset_names(), help = "system size preset: reduced (8 adipocytes, 400 cells), paper (28, 1500) or large (128, 7000)" },
    N_a = { 0, range = "[0, inf)", unit = "adipocytes", help = "number of adipocytes (0: from system)" },
    N_c = { 0, range = "[0, inf)", unit = "cells", help = "number of cancer cells (0: from system)" },
    L0 = { 0.0, range = "[0, inf)", unit = "sigma", help = "initial cubic box side (0: from system)" },
    seed = { 1, range = "[0, inf)", help = "random seed (placement, noise, orientations)" },
    phi = { 0.72, range = "(0, 1)", help = "total packing fraction reached by compression" },
    P = declare.engine("Dynamics.pressure_wall", "P", 1.3e-3),
    beta = declare.engine("Contacts", "beta", 1e-2, "the paper's 1e-2"),
    alpha = declare.engine("Contacts", "alpha"),
    beta_cv = declare.engine("Contacts", "beta_cv", nil, "docs/model.md, Forces"),
    alpha_cv = declare.engine("Contacts", "alpha_cv"),
    f0 = declare.engine("Active", "f0", 0.002, "0: passive cells; 0.002 with the default background: 2 k_B T_c/(P sigma^3) = 0.26 measured (docs/model.md), near the paper's Fig. 4b point 0.3"),
    tau_p = declare.engine("Active", "tau_p", 25.0),
    kT = { 0.0, range = "[0, inf)", unit = "eps_c", help = "background temperature of the cells and the langevin vertices (passive cells: their bath; active cells: only with background_factor = 0)" },
    background_factor = { 6.0, range = "[0, inf)", help = "active cells (f0 > 0): background temperature = this x the activity's free-particle temperature (f0/gamma)^2 tau/(3 (tau + m/gamma)), tau the persistence as the time step holds it (docs/model.md, Vertex bath); 0: the background is kT" },
    gamma = declare.engine("Active", "gamma", nil, "of the cancer cells"),
    vertex_bath = { "langevin", choices = { "langevin", "damped" }, help = "bath of the adipocyte vertices and the piston: langevin (FDT noise at kT) or damped (no noise)" },
    vertex_gamma = declare.engine("Langevin", "gamma", nil, "of the adipocyte vertices"),
    vertex_mass = { 1.0, range = "(0, inf)", unit = "m", help = "mass of each adipocyte vertex (the cells have m = 1)" },
    vertex_kT = { 0.0, range = "[0, inf)", unit = "eps_c", help = "noise temperature of langevin vertices (0: the background kT; refused > 0 with damped vertices)" },
    eps_v = declare.engine("Shape", "eps_v", 1e3),
    eps_a = declare.engine("Shape", "eps_a", 1.0),
    start = { "demixed", choices = { "demixed", "mixed" }, help = "initial placement: demixed (cells left of the adipocytes) or mixed (both over the whole box)" },
    adipocyte_spread = { 0.0, range = "[0, 1]", help = "adipocytes of many sizes: log-normal spread of their diameters, mean kept (0: one size, the paper; docs/model.md, Bodies)" },
    A_0 = { 1.1, range = "[1, inf)", help = "reference shape parameter of the adipocytes (a sphere has 1; the paper's Appendix A: 1.0, 1.1, 1.3)" },
    dt = declare.engine("Dynamics", "dt"),
    cohesive_compression = { false, help = "keep the cells' cohesion on during compression (default: repulsive packing)" },
    compress_ftol = { 1e-3, range = "(0, inf)", unit = "eps_c/sigma", help = "FIRE tolerance between compression steps" },
    final_ftol = { 1e-6, range = "(0, inf)", unit = "eps_c/sigma", help = "FIRE tolerance of the compressed tissue" },
    quench_steps = { 20000, range = "[0, inf)", help = "steps of the quench (wall to P, cells moving)" },
    steps = declare.keyword(production.keys, "steps"),
    every = declare.keyword(production.keys, "every"),
    snapshot_every = { 10000, range = "[0, inf)", help = "steps between snapshots (0: none)" },
    checkpoint_every = declare.keyword(production.keys, "checkpoint_every", 10000),
    correlate_every = declare.keyword(production.keys, "correlate_every"),
    lags = declare.keyword(production.keys, "lags"),
    origin_every = declare.keyword(production.keys, "origin_every"),
    lipolysis_rate = declare.engine("Lipolysis", "rate", 0.0, "0: no lipolysis, the paper; docs/model.md, Bodies"),
    lipolysis_floor = declare.engine("Lipolysis", "floor"),
    lipolysis_every = declare.keyword(production.keys, "lipolysis_every"),
    division_rate = declare.engine("Proliferation", "division_rate", 0.0, "0: no proliferation, the paper; docs/model.md, Proliferation and death"),
    death_rate = declare.engine("Proliferation", "death_rate"),
    inhibition_contacts = declare.engine("Proliferation", "inhibition_contacts"),
    proliferation_every = declare.keyword(production.keys, "proliferation_every"),
  }
end

-- Adds a protocol's own declarations to the common ones.
function M.merge(own)
  local all = M.declarations()
  for k, v in pairs(own or {}) do all[k] = v end
  return all
end

-- The init stage's keywords (lib/init.lua) from the parameters and the resolved size.
function M.init_options(p, N_a, N_c, L0)
  return { N_a = N_a, N_c = N_c, L0 = L0, seed = p.seed, start = p.start, shape_param = p.A_0,
           eps_v = p.eps_v, eps_a = p.eps_a, alpha = p.alpha, beta = p.beta,
           alpha_cv = p.alpha_cv, beta_cv = p.beta_cv, diameter_spread = p.adipocyte_spread }
end

-- The production stage's keywords from the parameters (run directory `out`), with `extra`
-- keys added or replacing them (a protocol's own choices, e.g. correlate_every = 0).
function M.production_options(p, out, extra)
  local o = { steps = p.steps, every = p.every, correlate_every = p.correlate_every,
              lags = p.lags, origin_every = p.origin_every,
              snapshot_every = p.snapshot_every, checkpoint_every = p.checkpoint_every, out = out,
              lipolysis_every = p.lipolysis_every }
  if p.lipolysis_rate > 0 then
    o.lipolysis = iv.Lipolysis{ rate = p.lipolysis_rate, floor = p.lipolysis_floor }
  end
  if p.division_rate > 0 or p.death_rate > 0 then
    o.proliferation = iv.Proliferation{ division_rate = p.division_rate, death_rate = p.death_rate,
                                        inhibition_contacts = p.inhibition_contacts }
    o.proliferation_every = p.proliferation_every
  end
  for k, v in pairs(extra or {}) do o[k] = v end
  return o
end

-- The system size after the preset and the explicit overrides.
function M.size(p)
  local preset = presets[p.system]
  if not preset then
    error(string.format("--set system=%s: unknown system; choose one of: %s", p.system,
                        table.concat(preset_names(), ", ")), 0)
  end
  return (p.N_a > 0 and p.N_a or preset.N_a), (p.N_c > 0 and p.N_c or preset.N_c),
         (p.L0 > 0 and p.L0 or preset.L0)
end

-- The combinations M.validate checks (it adds the caller's file and line to a refusal).
local function check_combinations(p)
  local N_a, N_c, L0 = M.size(p)
  -- The contact law's own rules (beta < alpha, beta_cv < alpha_cv), before any work.
  local problem = iv.Contacts.check{ alpha = p.alpha, beta = p.beta, alpha_cv = p.alpha_cv,
                                     beta_cv = p.beta_cv }
  if problem then
    error(problem .. " (--set alpha, beta, alpha_cv or beta_cv; beta = 0 switches cohesion off, beta_cv = 0 adhesion)", 0)
  end
  -- The step counter is a 64-bit integer (2^63 - 1 = math.maxinteger): the quench's and the
  -- production's steps together must fit in it.
  if p.quench_steps and p.steps and p.steps > math.maxinteger - p.quench_steps then
    error(string.format("steps: quench_steps + steps = %d + %d overflows the step counter " ..
                        "(at most %d steps in a run)", p.quench_steps, p.steps, math.maxinteger), 0)
  end
  require("lib.model_limits").check(p, N_a, N_c, L0)
  -- Active cells take their background temperature from background_factor unless it is 0.
  if p.f0 > 0 and p.background_factor > 0 and p.gamma == 0 then
    error(string.format("background_factor = %g needs gamma > 0 (the free-particle active " ..
                        "temperature (f0/gamma)^2 tau/(3 (tau + m/gamma)) is infinite at gamma = 0): " ..
                        "--set background_factor=0 or a gamma > 0", p.background_factor), 0)
  end
  if p.f0 > 0 and p.background_factor > 0 and p.kT > 0 then
    error(string.format("kT = %g and background_factor = %g both set the active cells' background " ..
                        "temperature: --set background_factor=0 to give kT yourself, or leave kT " ..
                        "at 0 (docs/model.md, Vertex bath)", p.kT, p.background_factor), 0)
  end
  local bad_kT = require("lib.motion").check_vertex_kT(p.vertex_bath, p.vertex_kT)
  if bad_kT then error(bad_kT .. ": --set vertex_bath=langevin, or leave vertex_kT at 0", 0) end
  -- Without friction a temperature has no bath (the Langevin noise sqrt(2 gamma kT m / dt) is 0)
  -- and a self-propulsion force no terminal speed (f0/gamma).
  if p.gamma == 0 and p.f0 > 0 then
    error(string.format("f0 = %g with gamma = 0: self-propelled cells without friction " ..
                        "accelerate without bound (their speed f0/gamma is infinite): --set gamma " ..
                        "> 0", p.f0), 0)
  end
  if p.gamma == 0 and p.kT > 0 then
    error(string.format("kT = %g with gamma = 0: the cells' Langevin noise sqrt(2 gamma kT m / dt) " ..
                        "is 0, so kT would do nothing: --set gamma > 0, or kT=0 for Newtonian " ..
                        "cells", p.kT), 0)
  end
  if p.vertex_bath == "langevin" and p.vertex_gamma == 0 and (p.vertex_kT or 0) > 0 then
    error(string.format("vertex_kT = %g with vertex_gamma = 0: the vertices' Langevin noise " ..
                        "sqrt(2 gamma kT m / dt) is 0, so vertex_kT would do nothing: --set " ..
                        "vertex_gamma > 0, or leave vertex_kT at 0", p.vertex_kT), 0)
  end
  if iv.from then M.check_from(p, iv.from) end
end

-- Checks the parameters' combinations before anything runs or any file is written (each
-- parameter's own range is checked by iv.params; lib/model_limits.lua refuses the values in
-- range that would make the run meaningless). A refusal names the protocol's line that calls
-- validate, as iv.params names its own.
function M.validate(p)
  local ok, err = pcall(check_combinations, p)
  if not ok then error(err, 2) end
end

-- The parameters whose effect is in the compressed tissue itself (the adipocytes' shapes and
-- sizes, the placement, the packing and how it was reached), besides the size.
local tissue_keys = { "A_0", "adipocyte_spread", "start", "phi", "cohesive_compression",
                      "compress_ftol", "final_ftol", "eps_v", "eps_a" }
-- The contact parameters the compression used when it kept the cells' cohesion on.
local cohesion_keys = { "beta", "alpha", "beta_cv", "alpha_cv" }

-- A run started --from DIR takes DIR's compressed tissue in place of its own: refuses, before
-- any work, a run whose own tissue would differ (a parameter of tissue_keys, of cohesion_keys
-- when DIR compressed with cohesion, or the initial box), naming the parameter, instead of
-- running the source's tissue under this run's value.
-- The seed may differ (it drives the dynamics from there on); DIR without params.json (a
-- script's own run directory) is not checked.
function M.check_from(p, from)
  local path = from .. "/params.json"
  if not iv.exists(path) then return end
  local source = iv.read_json(path).parameters or {}
  local function show(v) return type(v) == "number" and string.format("%g", v) or tostring(v) end
  local function refuse(key, theirs, ours)
    error(string.format("--from %s: its tissue was made with %s = %s, this run's is %s = %s; " ..
                        "the compressed tissue is the source's: --set %s=%s, or run without --from",
                        from, key, show(theirs), key, show(ours), key, show(theirs)), 0)
  end
  local function compare(keys)
    for _, key in ipairs(keys) do
      if source[key] ~= nil and p[key] ~= nil and source[key] ~= p[key] then
        refuse(key, source[key], p[key])
      end
    end
  end
  compare(tissue_keys)
  if source.cohesive_compression then compare(cohesion_keys) end
  -- The numbers of adipocytes and cells are compared by the checkpoint's loading (sites and
  -- bodies); the initial box, which compression scales, only here.
  if source.system and presets[source.system] and source.L0 then
    local theirs, ours = select(3, M.size(source)), select(3, M.size(p))
    if theirs ~= ours then
      error(string.format("--from %s: its tissue started from L0 = %s (system %s), this run's " ..
                          "would start from L0 = %s (system %s): give the source's L0, or run " ..
                          "without --from", from, show(theirs), source.system, show(ours),
                          p.system), 0)
    end
  end
end

return M
