-- Test: stage A + checkpoint + stage B equals one continuous run, bit for bit.
-- A tissue (cells active with thermal noise, damped vertices, tethers with heterogeneity, a
-- pressure wall with a pressure ramp, a correlator) runs 2N steps straight; the same
-- preparation run N steps, saved, then a freshly built copy loads the checkpoint and runs N
-- more: every position, velocity, orientation, the wall and the correlator sums agree
-- exactly, also across changes of the sites' engine order. Run with 1 and 2 threads by CTest,
-- with INVASIM_TEST_TEAM_STEPS=1 (src/integrate/test_hooks.hpp): at 2 threads the 1046 sites
-- then step in the parallel team, and the test requires that they did.
package.path = "../../protocols/?.lua;" .. package.path
local iv = require("invasim")
local p = iv.params{ steps = 400, seed = 3 }
local path = iv.out_dir .. "/state.ckpt"
iv.make_dirs(iv.out_dir)

local function build()
  local t = require("lib.init"){ N_a = 3, N_c = 920, L0 = 30.0, seed = p.seed, beta = 1e-2 }
  assert(t.sys:n_sites() >= 1024, "too few sites for the parallel team: " .. t.sys:n_sites())
  require("lib.compress")(t, { to_phi = 0.5, progress = false })
  require("lib.tether")(t, { K = 0.04, mean_degree = 2 })
  require("lib.heterogeneity")(t, { lambda = 0.3 })
  require("lib.quench")(t, { P = iv.ramp{ from = 1.3e-3, to = 2e-3, steps = 600 }, f0 = 0.02, tau_p = 5.0,
                             kT = 1e-4, steps = 100, progress = false })
  -- The sites' storage order chosen again every 64 steps: both stages cross several choices,
  -- and the checkpoint (step 500) falls between two, so the restored run must use the stored one.
  t.dyn:set_sort_every(64)
  t.correlator = iv.Correlator{ group = t.cells, interval = 10 * t.dyn:dt(), lags = 20, origin_every = 2 }
  return t
end

local team_steps = require("team_steps")
local function run(t, n)
  local before = t.dyn:parallel_steps()
  t.dyn:run(t.sys, n, { every = 10, callback = function() t.correlator:sample(t.sys) end })
  assert(t.dyn:parallel_steps() == before + team_steps(n),
         string.format("only %d of %d steps ran in the parallel team", t.dyn:parallel_steps() - before, n))
end

local function fingerprint(t)
  local parts = {}
  for _, r in ipairs(t.sys:positions()) do parts[#parts + 1] = string.format("%a %a %a", r[1], r[2], r[3]) end
  local box = t.sys:box()
  parts[#parts + 1] = string.format("lo %a wall %a %a", box.lo[1], t.dyn:wall_state().velocity, t.dyn:wall_state().P)
  parts[#parts + 1] = string.format("T %a %a", t.sys:temperature(t.cells), t.sys:temperature(t.vertices))
  local cols = t.correlator:result().columns
  for _, name in ipairs{ "cvv", "nn", "msd", "fs" } do
    for _, x in ipairs(cols[name]) do parts[#parts + 1] = string.format("%a", x) end
  end
  parts[#parts + 1] = string.format("step %d time %a", t.sys:step(), t.sys:time())
  return table.concat(parts, "\n")
end

local straight = build()
run(straight, 2 * p.steps)
local expected = fingerprint(straight)

local first = build()
run(first, p.steps)
iv.save_checkpoint(path, { system = first.sys, dynamics = first.dyn, tethers = first.tethers,
                           correlator = first.correlator, extra = "stage B next" })
run(first, p.steps)   -- the run that saved goes on unchanged too
assert(fingerprint(first) == expected, "saving a checkpoint changed the run")

local second = build()
local extra = iv.load_checkpoint(path, { system = second.sys, dynamics = second.dyn,
                                         tethers = second.tethers, correlator = second.correlator })
assert(extra == "stage B next", "extra: " .. extra)
-- The run identity sections: absent outside a run, stored and read back when given.
local id, text = iv.checkpoint_run(path)
assert(id == nil and text == nil, "a checkpoint saved without run_id has no run identity")
local stamped = iv.out_dir .. "/stamped.ckpt"
iv.save_checkpoint(stamped, { system = second.sys, run_id = iv.hash("a=1\n"), run_parameters = "a=1\n" })
id, text = iv.checkpoint_run(stamped)
assert(id == "ed9ed282c45f76f4" and id == iv.hash("a=1\n") and text == "a=1\n", "run identity: " .. tostring(id))
local ok, err = pcall(iv.save_checkpoint, stamped, { system = second.sys, run_parameters = "a=1\n" })
assert(not ok and err:find("run_parameters without run_id"), tostring(err))
assert(second.sys:step() == straight.sys:step() - p.steps, "restored step")
run(second, p.steps)
local got = fingerprint(second)
if got ~= expected then
  local a, b = {}, {}
  for line in expected:gmatch("[^\n]+") do a[#a + 1] = line end
  for line in got:gmatch("[^\n]+") do b[#b + 1] = line end
  for i = 1, math.max(#a, #b) do
    if a[i] ~= b[i] then error("FAILED: line " .. i .. " differs: " .. tostring(a[i]) .. " vs " .. tostring(b[i])) end
  end
end
print(string.format("checkpoint_continuation: identical after %d + %d steps (%d threads)", p.steps, p.steps, iv.threads()))
