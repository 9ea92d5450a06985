-- A checkpoint that load_checkpoint refuses (its Dynamics has a pressure wall, the one given
-- has none; its correlator has other lags) leaves every object given as it was: the System's
-- step, time and positions, the tethers, the contacts and the correlator. Prints a line per
-- case and "checkpoint_refused_changes_nothing: passed" at the end.
local iv = require("invasim")
local path = iv.out_dir .. "/saved.ckpt"
iv.make_dirs(iv.out_dir)

local function tissue()
  local sys = iv.System{ box = { 24, 16, 16 }, seed = 3 }
  sys:place{ cells = { n = 40, x = { 1, 5 } }, adipocytes = { n = 2, diameter = 6, vertex_diameter = 2, shape_param = 1.1, x = { 9, 20 } } }
  sys:add(iv.Walls{})
  local contacts = sys:add(iv.Contacts{})
  sys:add(iv.Shape{ eps_v = 1e3, eps_a = 1 })
  local dyn = iv.Dynamics{ dt = 0.01 }
  dyn:add(iv.Langevin{ group = sys:group("cancer"), kT = 1e-3 })
  dyn:add(iv.Damped{ group = sys:group("vertices") })
  return sys, dyn, contacts
end

-- The saved run: 10 steps with a pressure wall, tethers, other contacts and a sampled correlator.
local sys, dyn, contacts = tissue()
dyn:pressure_wall{ P = 1e-3 }
dyn:run(sys, 10)
contacts:set{ beta = 5e-3 }
local tethers = sys:add(iv.Tethers{ K = 1 })
tethers:connect{ mean_degree = 1 }
local correlator = iv.Correlator{ group = sys:group("cancer"), interval = 0.01, lags = 5 }
correlator:sample(sys)
iv.save_checkpoint(path, { system = sys, dynamics = dyn, tethers = tethers,
                           correlator = correlator, contacts = contacts })

local function state(s, t, c, k)
  local r = s:positions()
  return string.format("step %d time %.17g first %.17g last %.17g tethers %d beta %.17g samples %d",
                       s:step(), s:time(), r[1][1], r[#r][3], t:count(), c:params().beta,
                       k:samples())
end

local cases = {
  { "its Dynamics has a pressure wall", function(d) end, 5 },
  { "time correlator: restored velocity snapshots", function(d) d:pressure_wall{ P = 1e-3 } end, 7 },
}
for _, case in ipairs(cases) do
  local s, d, c = tissue()
  case[2](d)
  local t = s:add(iv.Tethers{ K = 2 })
  local k = iv.Correlator{ group = s:group("cancer"), interval = 0.01, lags = case[3] }
  local before = state(s, t, c, k)
  local ok, err = pcall(iv.load_checkpoint, path, { system = s, dynamics = d, tethers = t,
                                                     correlator = k, contacts = c })
  assert(not ok and tostring(err):find(case[1], 1, true), "refused for another reason: " .. tostring(err))
  local after = state(s, t, c, k)
  assert(after == before, "a refused load changed the objects:\n  " .. before .. "\n  " .. after)
  print("checkpoint_refused_changes_nothing: refused (" .. case[1] .. "), nothing changed")
end
print("checkpoint_refused_changes_nothing: passed")
