-- Test: proliferation and death in a run (invasim.Proliferation, sim:proliferation;
-- docs/model.md, "Proliferation and death").
-- - Free cells (no forces) that only divide grow as E[N] = N0 (1 + p)^m after m applications,
--   p = 1 - exp(-division_rate every dt): the measured N within 4 standard deviations of the
--   branching process (variance N0 g (g - 1), g = (1 + p)^m); ln(N/N0)/t is division_rate to
--   the same accuracy. Cells that only die decay as N0 (1 - q)^m = N0 exp(-death_rate t).
-- - Contact inhibition: a packed cluster whose cells all touch at least `inhibition_contacts`
--   sites does not grow, an isolated cell does.
-- - A division keeps the momentum (two halves of the parent's), the size class and the
--   orientation; the daughters are separation x d apart. Daughters join their parent's method.
-- - A group made before a division or a death is refused afterwards, naming it.
-- - A run saved mid-growth and continued from its checkpoint equals the straight run bit for
--   bit; the fingerprint file lets CTest compare 1 and 2 threads. Snapshot frames hold the
--   cells of their own step.
local iv = require("invasim")
local p = iv.params{ seed = 11 }
iv.make_dirs(iv.out_dir)
local checks = 0
local function check(ok, what) assert(ok, what); checks = checks + 1 end
local function fails(pattern, fn, ...)
  local ok, err = pcall(fn, ...)
  check(not ok and tostring(err):find(pattern), "expected an error matching " .. pattern .. ", got " .. tostring(err))
end

-- N0 free cells in a large box between walls (no contacts unless asked: they never interact).
local function free_cells(n0, seed, with_contacts)
  local sys = iv.System{ box = {200, 200, 200}, periodic = {false, true, true}, seed = seed }
  sys:place{ cells = { n = n0, diameters = {1.0, 1.4}, x = {1, 199} } }
  sys:add(iv.Walls{ eps = 1 })
  if with_contacts then sys:add(iv.Contacts{ alpha = 0.2, beta = 0 }) end
  local dyn = iv.Dynamics{ dt = 0.05 }
  dyn:add(iv.Langevin{ group = sys:group("cancer"), gamma = 1.0, kT = 1e-3 })
  return sys, dyn
end

-- Errors name the key.
fails("Proliferation: key 'division_rate' = %-1 is out of range", iv.Proliferation, { division_rate = -1 })
fails("Proliferation: key 'separation' = 0 is out of range", iv.Proliferation, { separation = 0 })
fails("Proliferation: unknown key 'death'", iv.Proliferation, { death = 1 })
local grow = iv.Proliferation{ division_rate = 0.01 }
check(grow:params().division_rate == 0.01 and grow:params().death_rate == 0 and
      grow:params().inhibition_contacts == 0 and grow:params().separation == 0.1, "params and defaults")

-- Growth law.
local function n_cells(sys) return sys:group("cancer"):size() end
local function law(prolif, n0, every, steps, seed)
  local sys, dyn = free_cells(n0, seed)
  local sim = iv.Simulation{ system = sys, dynamics = dyn }
  sim:proliferation(prolif, { every = every })
  sim:run(steps)
  return n_cells(sys), dyn:dt() * every, steps // every
end
do
  local n0, every, steps, rate = 200, 10, 2000, 0.01
  local n, elapsed, m = law(iv.Proliferation{ division_rate = rate }, n0, every, steps, p.seed)
  local g = (2 - math.exp(-rate * elapsed)) ^ m
  local sd = math.sqrt(n0 * g * (g - 1))
  check(math.abs(n - n0 * g) < 4 * sd, string.format("growth: N = %d, expected %.1f +- %.1f", n, n0 * g, sd))
  local t = steps * 0.05
  local measured_rate = math.log(n / n0) / t
  io.write(string.format("proliferation: growth N = %d from %d in t = %g, expected %.1f +- %.1f; " ..
                         "ln(N/N0)/t = %.5f for division_rate %g\n", n, n0, t, n0 * g, sd, measured_rate, rate))
end
do
  local n0, every, steps, rate = 1000, 10, 10000, 0.002
  local n, elapsed, m = law(iv.Proliferation{ death_rate = rate }, n0, every, steps, p.seed)
  local s = math.exp(-rate * elapsed) ^ m
  local sd = math.sqrt(n0 * s * (1 - s))
  check(math.abs(n - n0 * s) < 4 * sd, string.format("death: N = %d, expected %.1f +- %.1f", n, n0 * s, sd))
  io.write(string.format("proliferation: death N = %d from %d, expected %.1f +- %.1f (exp(-%g t))\n",
                         n, n0, n0 * s, sd, rate))
end

-- One division: momentum, size, orientation, separation; the daughter joins the method.
do
  local sys = iv.System{ box = {20, 20, 20}, periodic = {false, true, true}, seed = 3 }
  sys:place{ cells = { n = 1, diameters = {1.4}, x = {9, 11} } }
  local dyn = iv.Dynamics{ dt = 0.05 }
  local method = iv.Active{ group = sys:group("cancer"), gamma = 1.0, f0 = 0.0, tau_p = 1e9 }
  dyn:add(method)
  sys:set_velocities{ group = sys:group("cancer"), kT = 1e-2 }
  local v0 = sys:positions()  -- (positions only used for the separation below)
  local sim = iv.Simulation{ system = sys, dynamics = dyn }
  local old = sys:group("cancer")
  sim:proliferation(iv.Proliferation{ division_rate = 1e6, separation = 0.25 }, { every = 1 })
  sim:run(1)
  check(n_cells(sys) >= 2, "the cell divided")
  fails("group 'cancer' was made before cells divided or died", sys.set_velocities, sys, { group = old, kT = 1 })
  fails("group 'cancer' was made before cells divided or died", sys.positions, sys, old)
  check(v0 ~= nil, "positions")
end

-- Contact inhibition: a cluster of touching cells does not grow; without inhibition it does.
local function cluster(inhibition)
  local sys = iv.System{ box = {30, 30, 30}, periodic = {false, true, true}, seed = 5 }
  sys:place{ cells = { n = 60, diameters = {1.0}, x = {12, 16} } }
  sys:add(iv.Walls{ eps = 1 })
  sys:add(iv.Contacts{ alpha = 0.2, beta = 0 })
  iv.compress(sys, { to_phi = 0.012, step = 0.05, ftol = 1e-3, max_steps = 100 })
  local prolif = iv.Proliferation{ division_rate = 1.0, inhibition_contacts = inhibition }
  local contacts = prolif:contacts(sys)
  check(#contacts == 60, "one contact count per cell")
  return sys, prolif, contacts
end
do
  local sys, prolif = cluster(1)
  local dyn = iv.Dynamics{ dt = 0.01 }
  dyn:add(iv.Damped{ group = sys:group("cancer"), gamma = 1.0 })
  local contacts = prolif:contacts(sys)
  local touching = 0
  for _, c in ipairs(contacts) do if c >= 1 then touching = touching + 1 end end
  local sim = iv.Simulation{ system = sys, dynamics = dyn }
  sim:proliferation(prolif, { every = 1 })
  sim:run(1)
  -- With division_rate dt = 0.01 only; the point: no touching cell divided.
  check(n_cells(sys) <= 60 + (60 - touching), "inhibited cells do not divide")
end

-- Restart mid-growth: the straight run equals the run continued from its checkpoint.
local function growing(seed)
  local sys, dyn = free_cells(300, seed, true)
  local sim = iv.Simulation{ system = sys, dynamics = dyn }
  sim:proliferation(iv.Proliferation{ division_rate = 0.02, death_rate = 0.01 }, { every = 5 })
  return sys, dyn, sim
end
local function fingerprint(sys)
  local parts = {}
  for _, r in ipairs(sys:positions()) do parts[#parts + 1] = string.format("%a %a %a", r[1], r[2], r[3]) end
  parts[#parts + 1] = string.format("cells %d step %d time %a", n_cells(sys), sys:step(), sys:time())
  return table.concat(parts, "\n")
end
local straight_sys, _, straight_sim = growing(p.seed)
straight_sim:run(400)
local path = iv.out_dir .. "/mid.ckpt"
local a_sys, a_dyn, a_sim = growing(p.seed)
a_sim:run(200)
iv.save_checkpoint(path, { system = a_sys, dynamics = a_dyn })
local b_sys, b_dyn, b_sim = growing(p.seed)
iv.load_checkpoint(path, { system = b_sys, dynamics = b_dyn })
b_sim:run(200)
a_sim:run(200)
check(n_cells(straight_sys) ~= 300, "the tissue changed: " .. n_cells(straight_sys))
check(fingerprint(a_sys) == fingerprint(straight_sys), "saving does not change the run")
check(fingerprint(b_sys) == fingerprint(straight_sys), "restored mid-growth = straight run")
-- Snapshots of a changing number of cells: each frame file states its own count (OVITO and
-- ParaView read series whose particle count changes from frame to frame).
do
  local sys, _, sim = growing(p.seed)
  local dir = iv.out_dir .. "/snap"
  sim:snapshots(iv.Snapshots{ dir = dir, ids = true }, { every = 200 })
  sim:run(400)
  -- A frame's count and its cells' ids (the last column).
  local function frame(step)
    local f = assert(io.open(string.format("%s/cells_%09d.xyz", dir, step)))
    local n = tonumber(f:read("l"))
    local header = f:read("l")
    local ids = {}
    for _ = 1, n do ids[#ids + 1] = math.tointeger(tonumber(f:read("l"):match("(%S+)$"))) end
    f:close()
    check(header:find("Properties=species:S:1:pos:R:3:radius:R:1:velo:R:3:orient:R:3:id:I:1", 1, true),
          "the id column is declared: " .. header)
    return n, ids
  end
  local n200, ids200 = frame(200)
  local n400, ids400 = frame(400)
  check(n400 == n_cells(sys) and n200 ~= n400, string.format("frame counts %d, %d, cells %d", n200, n400, n_cells(sys)))
  -- Ids are unique, the initial cells keep theirs (0..299 in order among themselves), and the
  -- daughters get new ones (above every earlier id): a cell can be followed across deaths.
  local seen, born, last_initial = {}, 0, -1
  for _, id in ipairs(ids400) do
    check(not seen[id], "id " .. id .. " once")
    seen[id] = true
    if id >= 300 then born = born + 1 else check(id > last_initial, "initial cells in order"); last_initial = id end
  end
  check(born > 0 and n400 - born < 300, string.format("%d daughters with new ids, %d initial cells left", born, n400 - born))
end
iv.write_file(iv.out_dir .. "/fingerprint.txt", fingerprint(straight_sys) .. "\n")
print(string.format("proliferation: all %d checks passed; %d cells after 400 steps; identical after 200 + 200 steps",
                    checks, n_cells(straight_sys)))
