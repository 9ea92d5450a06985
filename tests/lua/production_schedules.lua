-- Test: the production stage's samplers each run on their own schedule (an iv.Simulation,
-- src/run/): with every = 300, snapshot_every = 700 and checkpoint_every = 500 (none a
-- multiple of another), series rows, snapshot frames and checkpoints come at exactly the
-- steps of the System that are multiples of their own period; the checkpoints also at the
-- run's last step (so that a resumed run ends on the same state.ckpt as an uninterrupted one).
package.path = "../../protocols/?.lua;" .. package.path
local iv = require("invasim")
local parameters = require("lib.parameters")
local stage = require("lib.stages")
local p = iv.params(parameters.declarations())
parameters.validate(p)
local out = require("lib.run_dir").open(p)
local N_a, N_c, L0 = parameters.size(p)
local tissue = stage.init{ N_a = N_a, N_c = N_c, L0 = L0, seed = p.seed, start = p.start,
                           shape_param = p.A_0, eps_v = p.eps_v, eps_a = p.eps_a,
                           alpha = p.alpha, beta = p.beta }
stage.compress(tissue, { to_phi = p.phi, ftol = p.compress_ftol, final_ftol = p.final_ftol,
                         cohesion = p.cohesive_compression })
stage.quench(tissue, { P = p.P, kT = p.kT, f0 = p.f0, tau_p = p.tau_p, gamma = p.gamma,
                       vertex_bath = p.vertex_bath, vertex_gamma = p.vertex_gamma, dt = p.dt,
                       steps = p.quench_steps })
local first = tissue.sys:step()
local result = stage.production(tissue, { steps = p.steps, every = p.every,
                                          correlate_every = p.correlate_every,
                                          snapshot_every = p.snapshot_every,
                                          checkpoint_every = p.checkpoint_every, out = out })
local last = tissue.sys:step()
assert(last == first + p.steps, "production ran " .. (last - first) .. " steps")

local function multiples(period, lo, hi)   -- steps s in (lo, hi] with s % period == 0
  local t = {}
  for s = lo + 1, hi do if s % period == 0 then t[#t + 1] = s end end
  return t
end
local function same(a, b, what)
  assert(#a == #b, string.format("%s: %d entries, expected %d", what, #a, #b))
  for i = 1, #a do
    assert(a[i] == b[i], string.format("%s: entry %d is step %s, expected %s", what, i, a[i], b[i]))
  end
  return #a
end

local rows = {}
for i, row in ipairs(result.series.rows) do rows[i] = row.step end
local n_rows = same(rows, multiples(p.every, first, last), "series rows")

local frames = {}
for line in assert(io.open(out .. "/snapshots/adipocytes.pvd")):lines() do
  local step = line:match('file="adipocytes_(%d+)%.vtp"')
  if step then frames[#frames + 1] = tonumber(step) end
end
local expected_frames = multiples(p.snapshot_every, first, last)
table.insert(expected_frames, 1, first)  -- the frame of the start (stage.production)
local n_frames = same(frames, expected_frames, "snapshot frames")

local checkpoints = {}
for line in assert(io.open(out .. "/log.txt")):lines() do
  local step = line:match("^production: checkpoint of step (%d+) written")
  if step then checkpoints[#checkpoints + 1] = tonumber(step) end
end
local expected_checkpoints = multiples(p.checkpoint_every, first, last)
if last % p.checkpoint_every ~= 0 then expected_checkpoints[#expected_checkpoints + 1] = last end
local n_checkpoints = same(checkpoints, expected_checkpoints, "checkpoints")
assert(n_checkpoints > 0 and n_frames > 1 and n_rows > 0, "the schedules must fire")
print(string.format("production_schedules: ok (%d rows, %d frames, %d checkpoints at their own steps)",
                    n_rows, n_frames, n_checkpoints))
