-- Test: lipolysis in a run (invasim.Lipolysis, sim:lipolysis; docs/model.md, "Beyond the
-- paper"). Touched adipocytes shrink by rate x v_0(initial) x N dt every N steps, keep their
-- reference shape parameter, stop at the floor; untouched ones keep v_0. A run saved after N
-- steps and continued from its checkpoint equals the straight run bit for bit (reference
-- volumes included); the fingerprint file lets CTest compare 1 and 2 threads (1046 sites: at 2
-- threads with INVASIM_TEST_TEAM_STEPS=1, src/integrate/test_hooks.hpp, set by CTest, the
-- steps run in the parallel team, and the test requires that they did). Bad keys are refused,
-- naming them.
package.path = "../../protocols/?.lua;" .. package.path
local iv = require("invasim")
local p = iv.params{ steps = 300, seed = 5 }
local path = iv.out_dir .. "/state.ckpt"
iv.make_dirs(iv.out_dir)
local checks = 0
local function check(ok, what) assert(ok, what); checks = checks + 1 end
local function fails(pattern, fn, ...)
  local ok, err = pcall(fn, ...)
  check(not ok and tostring(err):find(pattern), "expected an error matching " .. pattern .. ", got " .. tostring(err))
end

local function build()
  local t = require("lib.init"){ N_a = 3, N_c = 920, L0 = 30.0, seed = p.seed, beta = 1e-2 }
  check(t.sys:n_sites() >= 1024, "enough sites for the parallel team: " .. t.sys:n_sites())
  require("lib.compress")(t, { to_phi = 0.55, progress = false })
  require("lib.quench")(t, { P = 1.3e-3, f0 = 0.02, tau_p = 5.0, kT = 1e-4, steps = 100, progress = false })
  t.dyn:set_sort_every(64)
  return t
end
local lip = iv.Lipolysis{ rate = 2e-3, floor = 0.8 }
local every = 10

local team_steps = require("team_steps")
local function run(t, n)
  local sim = iv.Simulation{ system = t.sys, dynamics = t.dyn }
  sim:lipolysis(lip, { every = every })
  local before = t.dyn:parallel_steps()
  sim:run(n)
  check(t.dyn:parallel_steps() == before + team_steps(n),
        string.format("%d of %d steps in the parallel team", t.dyn:parallel_steps() - before, n))
end

local function volumes(t)
  local v = {}
  for _, a in ipairs(t.sys:adipocytes()) do v[#v + 1] = a end
  return v
end

local function fingerprint(t)
  local parts = {}
  for _, r in ipairs(t.sys:positions()) do parts[#parts + 1] = string.format("%a %a %a", r[1], r[2], r[3]) end
  for _, a in ipairs(t.sys:adipocytes()) do
    parts[#parts + 1] = string.format("v0 %a %a A0 %a", a.ref_volume, a.ref_volume_initial, a.ref_shape_parameter)
  end
  parts[#parts + 1] = string.format("step %d time %a", t.sys:step(), t.sys:time())
  return table.concat(parts, "\n")
end

-- Errors name the key.
fails("Lipolysis: missing required key 'rate'", iv.Lipolysis, {})
fails("Lipolysis: key 'rate' = %-1 is out of range", iv.Lipolysis, { rate = -1 })
fails("Lipolysis: key 'floor' = 0 is out of range", iv.Lipolysis, { rate = 1, floor = 0 })
fails("Lipolysis: unknown key 'flor'", iv.Lipolysis, { rate = 1, flor = 0.5 })
check(lip:params().rate == 2e-3 and lip:params().floor == 0.8, "params")

local straight = build()
local before = volumes(straight)
local touched = lip:touched(straight.sys)
check(#touched == straight.sys:n_adipocytes(), "one entry per adipocyte")
local n_touched = 0
for _, t in ipairs(touched) do if t then n_touched = n_touched + 1 end end
check(n_touched >= 1, "the compressed, de-mixed tissue has cells touching adipocytes")
fails("lipolysis: missing required key 'every'", iv.Simulation{ system = straight.sys, dynamics = straight.dyn }.lipolysis,
      iv.Simulation{ system = straight.sys, dynamics = straight.dyn }, lip, {})
fails("Lipolysis expected", iv.Simulation{ system = straight.sys, dynamics = straight.dyn }.lipolysis,
      iv.Simulation{ system = straight.sys, dynamics = straight.dyn }, "x", { every = 1 })
fails("elapsed time %-1 must be >= 0", lip.apply, lip, straight.sys, -1)

run(straight, 2 * p.steps)
local after = volumes(straight)
local shrunk = 0
for b, a in ipairs(after) do
  local loss = before[b].ref_volume - a.ref_volume
  local step_loss = 2e-3 * a.ref_volume_initial * every * straight.dyn:dt()
  -- Whole applications only (rounding aside), at most 2 p.steps / every of them.
  local k = loss / step_loss
  check(math.abs(k - math.floor(k + 0.5)) < 1e-6 and k <= 2 * p.steps / every + 1e-9, "whole applications: " .. k)
  check(a.ref_volume >= 0.8 * a.ref_volume_initial * (1 - 1e-12), "the floor")
  check(math.abs(a.ref_shape_parameter - before[b].ref_shape_parameter) < 1e-12 * before[b].ref_shape_parameter,
        "the reference shape parameter is kept")
  if loss > 0 then shrunk = shrunk + 1 end
end
check(shrunk >= 1, "touched adipocytes shrank")
local expected = fingerprint(straight)

local first = build()
run(first, p.steps)
iv.save_checkpoint(path, { system = first.sys, dynamics = first.dyn })
local second = build()
iv.load_checkpoint(path, { system = second.sys, dynamics = second.dyn })
run(second, p.steps)
check(fingerprint(second) == expected, "the run continued from its checkpoint differs from the straight run")
require("lib.files").write(iv.out_dir .. "/fingerprint.txt", expected .. "\n")
print(string.format("lipolysis: all %d checks passed; %d of %d adipocytes shrank; identical after %d + %d steps",
                    checks, shrunk, #after, p.steps, p.steps))
