-- Pieces shared by the protocols in this directory: the parameters every invasion protocol
-- declares (one place, so invasion.lua, tethered.lua and packing.lua agree), and the chain
-- init -> compress -> quench with those parameters.
local presets = require("lib.presets")

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
    P = { 1.3e-3, range = "[0, inf)", unit = "eps_c/sigma^3", help = "pressure on the left wall" },
    beta = { 1e-2, range = "[0, inf)", help = "cancer-cell cohesion depth (0: repulsive; below alpha)" },
    alpha = { 0.2, range = "[0, inf)", help = "cancer-cell cohesion range" },
    f0 = { 0.01, range = "[0, inf)", unit = "eps_c/sigma", help = "self-propulsion force (0: passive cells)" },
    tau_p = { 25.0, range = "[0, inf)", unit = "tau", help = "persistence time of the active orientation (0: uncorrelated)" },
    kT = { 0.0, range = "[0, inf)", unit = "eps_c", help = "thermal noise temperature of the cells" },
    gamma = { 0.2, range = "[0, inf)", unit = "sqrt(m eps_c)/sigma", help = "damping coefficient of the cancer cells" },
    vertex_bath = { "langevin", choices = { "langevin", "damped" }, help = "bath of the adipocyte vertices and the piston: langevin (FDT noise at kT) or damped (no noise)" },
    vertex_gamma = { 0.2, range = "[0, inf)", unit = "sqrt(m eps_c)/sigma", help = "damping coefficient of the adipocyte vertices" },
    eps_v = { 1e3, range = "[0, inf)", unit = "eps_c", help = "adipocyte volume stiffness" },
    eps_a = { 1.0, range = "[0, inf)", unit = "eps_c", help = "adipocyte face-area stiffness" },
    start = { "demixed", choices = { "demixed", "mixed" }, help = "initial placement: demixed (cells left of the adipocytes) or mixed (both over the whole box)" },
    A_0 = { 1.1, range = "[1, inf)", help = "reference shape parameter of the adipocytes (a sphere has 1; the paper's Appendix A: 1.0, 1.1, 1.3)" },
    dt = { 0.05, range = "(0, inf)", unit = "tau", help = "time step" },
    cohesive_compression = { false, help = "keep the cells' cohesion on during compression (default: repulsive packing)" },
    compress_ftol = { 1e-3, range = "(0, inf)", unit = "eps_c/sigma", help = "FIRE tolerance between compression steps" },
    final_ftol = { 1e-6, range = "(0, inf)", unit = "eps_c/sigma", help = "FIRE tolerance of the compressed tissue" },
    quench_steps = { 20000, type = "integer", range = "[0, inf)", help = "steps of the quench (wall to P, cells moving)" },
    steps = { 100000, type = "integer", range = "[0, inf)", help = "production steps" },
    every = { 1000, type = "integer", range = "[1, inf)", help = "steps between measurements (a row of series.csv)" },
    snapshot_every = { 10000, type = "integer", range = "[0, inf)", help = "steps between snapshots (0: none)" },
    checkpoint_every = { 10000, type = "integer", range = "[0, inf)", help = "steps between checkpoints (0: only on SIGINT/SIGTERM)" },
    correlate_every = { 20, type = "integer", range = "[0, inf)", help = "steps between correlator samples (0: none)" },
  }
end

-- Adds a protocol's own declarations to the common ones.
function M.merge(own)
  local all = M.declarations()
  for k, v in pairs(own or {}) do all[k] = v end
  return all
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

-- The production stage with the common parameters, writing into the run directory `out`,
-- with snapshots at the steps that are multiples of snapshot_every (and one at the start).
function M.produce(tissue, p, out)
  local iv = require("invasim")
  local snapshots
  if p.snapshot_every > 0 and out then
    snapshots = iv.Snapshots{ dir = out .. "/snapshots" }
    if not require("lib.resume").pending() then snapshots:write(tissue.sys) end
  end
  return require("lib.production")(tissue, {
    steps = p.steps, every = p.every, correlate_every = p.correlate_every, out = out,
    checkpoint_every = p.checkpoint_every,
    on_sample = snapshots and function(row)
      if row.step % p.snapshot_every == 0 then snapshots:write(tissue.sys) end
    end or nil,
  })
end

-- Checks the parameters' combinations before anything runs or any file is written (each
-- parameter's own range is checked by iv.params).
function M.validate(p)
  M.size(p)
  if p.beta > 0 and p.beta >= p.alpha then
    error(string.format("cohesion: beta = %g must be smaller than alpha = %g (--set beta=... or --set alpha=...; beta = 0 switches cohesion off)",
                        p.beta, p.alpha), 0)
  end
  if p.snapshot_every > 0 and p.snapshot_every % p.every ~= 0 then
    error(string.format("--set snapshot_every=%d must be a multiple of every = %d", p.snapshot_every, p.every), 0)
  end
  if p.checkpoint_every > 0 and p.checkpoint_every % p.every ~= 0 then
    error(string.format("--set checkpoint_every=%d must be a multiple of every = %d", p.checkpoint_every, p.every), 0)
  end
end

-- init + compress with the common parameters; returns the tissue. With --from RUN_DIR, the
-- compressed tissue that run saved (RUN_DIR/checkpoint/compressed.ckpt) replaces the
-- compression (the paper's sweeps share one compressed tissue): same system size, this
-- run's seed.
function M.compressed(p, out)
  local iv = require("invasim")
  local resume = require("lib.resume")
  local N_a, N_c, L0 = M.size(p)
  local tissue = require("lib.init"){
    N_a = N_a, N_c = N_c, L0 = L0, seed = p.seed, eps_v = p.eps_v, eps_a = p.eps_a,
    alpha = p.alpha, beta = p.beta, shape_param = p.A_0, start = p.start,
  }
  if iv.from and not resume.pending() then
    local path = resume.compressed_path(iv.from)
    local saved = resume.deserialize(iv.load_checkpoint(path, { system = tissue.sys, seed = p.seed }))
    saved.from = path
    tissue.compression = saved
    require("lib.log").say("compress", "skipped: the compressed tissue of %s (box %.4g, phi = %.4f)",
                           iv.from, saved.box[1], saved.phi)
  else
    tissue.compression = require("lib.compress")(tissue, {
      to_phi = p.phi, ftol = p.compress_ftol, final_ftol = p.final_ftol,
      beta = p.cohesive_compression and p.beta or 0.0,
      save = out and resume.compressed_path(out) or nil,
      checkpoint = out and resume.compressing_path(out) or nil,
    })
  end
  return tissue
end

-- The quench with the common parameters (pressure wall at P, the cells' motion).
function M.quench(tissue, p)
  return require("lib.quench")(tissue, { P = p.P, kT = p.kT, f0 = p.f0, tau_p = p.tau_p,
                                         gamma = p.gamma, vertex_bath = p.vertex_bath,
                                         vertex_gamma = p.vertex_gamma, dt = p.dt,
                                         steps = p.quench_steps })
end

-- init + compress (or --from) + quench with the common parameters; returns the tissue.
-- (Protocols with tethers call compressed(), insert them, then quench(): docs/model.md, protocol step 4.)
function M.prepare(p, out)
  local tissue = M.compressed(p, out)
  return M.quench(tissue, p)
end

return M
