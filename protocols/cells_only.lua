-- Active repulsive cancer cells without adipocytes in a fully periodic cubic box (the paper's
-- Fig. 6): C_vv(t) and tau_d against tau_p at a packing fraction phi_c, beside the exact
-- free-particle value (lib/free_active.lua). N_c bidisperse cells (0.9 / 1.1) are placed at
-- random without overlaps over the whole box; phi_c <= place_phi is placed directly (random
-- sequential addition jams near 0.38), a denser phi_c is placed at place_phi and compressed
-- with FIRE (lib/compress.lua, repulsive contacts). phi_c = 0 means free particles: no
-- contacts at all (box of place_phi). Then Active cells (f0, tau_p, gamma, kT) run
-- equilibrate_steps and a production with the correlators; summary.json and the printout
-- give tau_d (the paper's per-particle normalisation), tau_d_standard and tau_d_free.
--   invasim run protocols/cells_only.lua --set phi_c=0.5 --set tau_p=250
local iv = require("invasim")
local declare = require("lib.declare")
local free = require("lib.free_active")
local production = require("lib.production")
local log = require("lib.log")

local p = iv.params{
  N_c = { 1000, range = "[2, inf)", unit = "cells", help = "number of cancer cells (bidisperse 0.9 / 1.1)" },
  phi_c = { 0.3, range = "[0, 0.6]", help = "packing fraction of the cells (0: free particles, no contacts)" },
  seed = { 1, range = "[0, inf)", help = "random seed (placement, orientations, noise)" },
  f0 = declare.engine("Active", "f0", 0.01, "here > 0: active cells"),
  tau_p = declare.engine("Active", "tau_p", 25.0, "here 0 < tau_p < inf: the free particle's tau_d needs a finite persistence"),
  kT = declare.engine("Active", "kT", nil, "the free formula assumes 0"),
  gamma = declare.engine("Active", "gamma", nil, "here > 0: tau_g = m / gamma"),
  dt = declare.engine("Dynamics", "dt"),
  place_phi = { 0.2, range = "(0, 0.3]", help = "packing fraction of the random placement (random placement jams near 0.38); a larger phi_c is reached by compression" },
  ftol = { 1e-6, range = "(0, inf)", unit = "eps_c/sigma", help = "FIRE tolerance of the compressed packing" },
  equilibrate_steps = { -1, range = "[-1, inf)", type = "integer", help = "steps before measuring (-1: max(10 tau_g, 2 tau_p) / dt)" },
  steps = { -1, range = "[-1, inf)", type = "integer", help = "production steps (-1: 10 correlation windows; 0 is refused)" },
  window = { 0.0, range = "[0, inf)", unit = "tau", help = "correlation window (0: 4 x the free-particle tau_d)" },
  lags = { 200, range = "[2, inf)", type = "integer", help = "correlator lags in the window" },
  every = { 1000, range = "[1, inf)", type = "integer", help = "steps between rows of series.csv" },
  checkpoint_every = declare.keyword(production.keys, "checkpoint_every"),
}

local function fail(fmt, ...) error(string.format(fmt, ...), 2) end
-- Each parameter's own range is checked by iv.params; these are the combinations.
if p.steps == 0 then fail("--set steps=0: must be > 0 (-1: automatic)") end
if not (p.f0 > 0) then fail("--set f0=%g: must be > 0 here (active cells)", p.f0) end
if not (p.gamma > 0) then fail("--set gamma=%g: must be > 0 here (tau_g = m / gamma)", p.gamma) end
if not (p.tau_p > 0 and p.tau_p < math.huge) then
  fail("--set tau_p=%g: must be > 0 and finite here (the free particle's tau_d needs a finite persistence)", p.tau_p)
end
local ok, err = pcall(require("lib.model_limits").check_dynamics, p)  -- values in range that mean nothing
if not ok then error(err, 1) end

-- Times: tau_g, the free particle's tau_d, the correlation window and the run lengths.
local tau_g = 1.0 / p.gamma
local tau_d_free = free.tau_d(p.tau_p, tau_g)
local window = p.window > 0 and p.window or 4 * tau_d_free
local correlate_every = math.max(1, math.floor(window / (p.lags * p.dt) + 0.5))
window = p.lags * correlate_every * p.dt
local equilibrate = p.equilibrate_steps >= 0 and p.equilibrate_steps
                    or math.ceil(math.max(10 * tau_g, 2 * p.tau_p) / p.dt)
local steps = p.steps > 0 and p.steps or math.ceil(10 * window / p.dt)
if steps < p.every then fail("steps = %d is less than every = %d: no samples to average", steps, p.every) end

local clock = iv.clock()
local out = require("lib.run_dir").open(p)
local resume = require("lib.resume")

-- The box: cubic, periodic in x, y and z, of side L such that the cells fill phi.
local diameters = { 0.9, 1.1 }
local volume = 0
for i = 0, p.N_c - 1 do volume = volume + math.pi / 6 * diameters[i % 2 + 1] ^ 3 end
local compress = p.phi_c > p.place_phi
local L = (volume / ((p.phi_c > 0 and not compress) and p.phi_c or p.place_phi)) ^ (1 / 3)
local sys = iv.System{ box = { L, L, L }, periodic = { true, true, true }, seed = p.seed }
sys:place{ cells = { n = p.N_c, x = { 0, L }, diameters = diameters } }
local tissue = { sys = sys, cells = sys:group("cancer") }
if p.phi_c > 0 then tissue.contacts = sys:add(iv.Contacts{ alpha = 0.2, beta = 0.0 }) end
local periodic = sys:box().periodic
log.say("init", "%d cells in a box %s periodic in x, y, z: %s %s %s; phi_c = %.4f%s", tissue.cells:size(),
        log.box(sys:box().lengths), tostring(periodic[1]), tostring(periodic[2]), tostring(periodic[3]),
        sys:packing().cancer,
        p.phi_c > 0 and " (repulsive contacts)" or " (free particles: no contacts)")
if compress then
  tissue.compression = require("lib.compress")(tissue, { to_phi = p.phi_c, final_ftol = p.ftol, progress = false })
end

local dyn = iv.Dynamics{ dt = p.dt }
tissue.cell_method = dyn:add(iv.Active{ group = tissue.cells, gamma = p.gamma, f0 = p.f0,
                                        tau_p = p.tau_p, kT = p.kT })
tissue.dyn = dyn
log.say("equilibrate", "active cells (f0 = %g, tau_p = %g, kT = %g, gamma = %g), %d steps of dt = %g",
        p.f0, p.tau_p, p.kT, p.gamma, equilibrate, p.dt)
if resume.pending() then
  log.say("equilibrate", "steps skipped: resuming from a checkpoint")
else
  dyn:run(sys, equilibrate, { every = 1000 })
  local signal = iv.interrupted()
  if signal then fail("stopped by %s while equilibrating at step %d; run the protocol again", signal, sys:step()) end
end

local result = production(tissue, {
  steps = steps, every = p.every, correlate_every = correlate_every, lags = p.lags, out = out,
  checkpoint_every = p.checkpoint_every, slices_per_body = 0,
})
local s = result.summary

-- Side by side: measured tau_d (both normalisations) and the free particle's.
local function opt(x, name)
  return x and (string.format("%.4g", x) .. (s[name .. "_unresolved"] and " (unresolved)" or "")) or "not reached"
end
log.say("summary", "%d cells, phi_c = %.4f, box %s; t = %g (%d steps); wall-clock %.1f s", tissue.cells:size(),
        sys:packing().cancer, log.box(sys:box().lengths), sys:time(), sys:step(), iv.clock() - clock)
log.say("summary", "T_c = %.4g (paper's convention %.4g); tau_g = %g, tau_p = %g, window %g",
        s.T_c.mean, 2 * s.T_c.mean, tau_g, p.tau_p, s.correlation_window)
log.say("summary", "tau_d = %s (paper's per-particle C_vv), tau_d_standard = %s, tau_d_free = %.4g (free-particle formula%s)",
        opt(s.tau_d, "tau_d"), opt(s.tau_d_standard, "tau_d_standard"), tau_d_free, p.kT > 0 and ", exact only for kT = 0" or "")
if s.tau_d_standard then
  log.say("summary", "tau_d_standard / tau_d_free = %.4f", s.tau_d_standard / tau_d_free)
end
if out then
  require("lib.files").write(out .. "/summary.json", iv.json_encode{
    N_c = tissue.cells:size(), phi_c = sys:packing().cancer, box = sys:box().lengths,
    tau_g = tau_g, tau_p = p.tau_p, f0 = p.f0, kT = p.kT,
    tau_d = s.tau_d, tau_d_standard = s.tau_d_standard, tau_d_free = tau_d_free,
    tau_d_unresolved = s.tau_d_unresolved, tau_d_standard_unresolved = s.tau_d_standard_unresolved,
    correlation_window = s.correlation_window, correlate_every = correlate_every,
    equilibrate_steps = equilibrate, steps = sys:step(), time = sys:time(),
    averages = { T_c = s.T_c, phi_c = s.phi_c, L_x = s.L_x }, samples = s.samples,
    compression = tissue.compression and { phi = tissue.compression.phi, steps = tissue.compression.steps,
                                           max_force = tissue.compression.max_force } or nil,
    wall_clock_seconds = iv.clock() - clock,
  })
  log.say("summary", "results in %s (series.csv, summary.json, correlations.csv)", out)
end
