-- Test: proliferation and death in a run (invasim.Proliferation, sim:proliferation;
-- docs/model.md, "Proliferation and death").
-- - Free cells (no forces) that only divide grow as E[N] = N0 (1 + p)^m after m applications,
--   p = 1 - exp(-division_rate every dt): the measured N within 4 standard deviations of the
--   branching process (variance N0 g (g - 1), g = (1 + p)^m); ln(N/N0)/t is division_rate to
--   the same accuracy. Cells that only die decay as N0 (1 - q)^m = N0 exp(-death_rate t).
-- - Contact inhibition: when every cell is sure to divide, the cells touching at least
--   `inhibition_contacts` others do not, the others do.
-- - A division gives each daughter half the parent's velocity and its orientation; the
--   daughters are separation x d apart. Daughters join their parent's method.
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

-- One division: each daughter has half the parent's velocity (the momentum is shared in
-- halves) and its orientation, the two sit separation x d apart, and the daughter joins the
-- parent's method (the next step damps both alike; a site outside every method would keep its
-- velocity: no force acts). The parent's state at the division is the same run's without
-- proliferation (no noise: the step is deterministic). (Sizes: test_proliferation.)
do
  local function one_cell(divide)
    local sys = iv.System{ box = {20, 20, 20}, periodic = {false, true, true}, seed = 3 }
    sys:place{ cells = { n = 1, diameters = {1.4}, x = {9, 11} } }
    local dyn = iv.Dynamics{ dt = 0.05 }
    dyn:add(iv.Active{ group = sys:group("cancer"), gamma = 1.0, f0 = 0.0, tau_p = 1e9 })
    sys:set_velocities{ group = sys:group("cancer"), kT = 1e-2 }
    local old = sys:group("cancer")
    local sim = iv.Simulation{ system = sys, dynamics = dyn }
    if divide then
      sim:proliferation(iv.Proliferation{ division_rate = 1e6, separation = 0.25 }, { every = 1 })
    end
    sim:run(1)
    return sys, dyn, old, sim
  end
  local parent = one_cell(false)
  local sys, dyn, old, sim = one_cell(true)
  check(n_cells(sys) == 2, "the cell divided once: " .. n_cells(sys) .. " cells")
  local v0, n0 = parent:velocities()[1], parent:orientations()[1]
  check(v0[1] ~= 0 and v0[2] ~= 0 and v0[3] ~= 0, "the parent moves")
  local r, v, n = sys:positions(), sys:velocities(), sys:orientations()
  for k = 1, 2 do
    for a = 1, 3 do
      check(v[k][a] == 0.5 * v0[a], string.format("daughter %d: velocity %g, half of %g", k, v[k][a], v0[a]))
      check(n[k][a] == n0[a], string.format("daughter %d: orientation %g, the parent's %g", k, n[k][a], n0[a]))
    end
  end
  local d2 = (r[1][1] - r[2][1]) ^ 2  -- x: walls; y, z: periodic with L = 20 (minimum image)
  for a = 2, 3 do d2 = d2 + (((r[1][a] - r[2][a]) + 10) % 20 - 10) ^ 2 end
  check(math.abs(math.sqrt(d2) - 0.25 * 1.4) < 1e-12,
        string.format("daughters %.15g apart, separation x d = 0.35", math.sqrt(d2)))
  sim:run(1)
  local after = sys:velocities()
  for a = 1, 3 do
    check(after[1][a] == after[2][a] and after[2][a] ~= v[2][a], "both daughters damped by the parent's method")
  end
  check(dyn:methods()[1]:kind() == "Active", "one method")
  fails("group 'cancer' was made before cells divided or died", sys.set_velocities, sys, { group = old, kT = 1 })
  fails("group 'cancer' was made before cells divided or died", sys.positions, sys, old)
end

-- A group naming sites the System no longer has is refused, also at an unchanged epoch: a
-- checkpoint of fewer cells, divided as often, loaded since the group was made.
do
  local function divided(n)
    local sys = iv.System{ box = {20, 20, 20}, periodic = {false, true, true}, seed = 3 }
    sys:place{ cells = { n = n, diameters = {1.0}, x = {5, 15} } }
    local dyn = iv.Dynamics{ dt = 0.05 }
    dyn:add(iv.Damped{ group = sys:group("cancer"), gamma = 1.0 })
    local sim = iv.Simulation{ system = sys, dynamics = dyn }
    sim:proliferation(iv.Proliferation{ division_rate = 1e6 }, { every = 1 })
    sim:run(1)
    return sys
  end
  local small, big = divided(2), divided(5)
  check(n_cells(small) == 4 and n_cells(big) == 10, "one division each")
  local g = big:group("cancer")
  local path = iv.out_dir .. "/small.ckpt"
  iv.save_checkpoint(path, { system = small })
  iv.load_checkpoint(path, { system = big })
  fails("positions: group 'cancer' names site index 4 but the System has 4 sites now", big.positions, big, g)
  fails("temperature: group 'cancer' names site index 4 but the System has 4 sites now", big.temperature, big, g)
end

-- Contact inhibition: with a division certain at the next application (division_rate x dt
-- = 1e4), a cell touching at least `inhibition_contacts` others does not divide and every
-- other cell does; without inhibition every cell divides.
-- The cells' contacts are counted where the application counts them, after the step: on a
-- twin run one step without proliferation (no noise: the same step).
local function cluster(inhibition)
  local function packed(prolif)
    local sys = iv.System{ box = {30, 30, 30}, periodic = {false, true, true}, seed = 5 }
    sys:place{ cells = { n = 60, diameters = {1.0}, x = {12, 16} } }
    sys:add(iv.Walls{ eps = 1 })
    sys:add(iv.Contacts{ alpha = 0.2, beta = 0 })
    iv.compress(sys, { to_phi = 0.2, step = 0.05, ftol = 1e-3, max_steps = 100 })
    local dyn = iv.Dynamics{ dt = 0.01 }
    dyn:add(iv.Damped{ group = sys:group("cancer"), gamma = 1.0 })
    local sim = iv.Simulation{ system = sys, dynamics = dyn }
    if prolif then sim:proliferation(prolif, { every = 1 }) end
    sim:run(1)
    return sys
  end
  local prolif = iv.Proliferation{ division_rate = 1e6, inhibition_contacts = inhibition }
  local contacts = prolif:contacts(packed(nil))
  check(#contacts == 60, "one contact count per cell")
  return n_cells(packed(prolif)), contacts
end
do
  local n, contacts = cluster(1)
  local touching = 0
  for _, c in ipairs(contacts) do if c >= 1 then touching = touching + 1 end end
  check(touching >= 2 and touching <= 58, touching .. " of 60 cells touch: both kinds needed")
  check(n == 60 + (60 - touching),
        string.format("inhibition: %d cells from 60, %d touching: expected %d", n, touching, 120 - touching))
  check(cluster(0) == 120, "without inhibition every cell divides")
  io.write(string.format("proliferation: inhibition: %d of 60 cells touch; %d cells after one application\n",
                         touching, n))
end

-- Restart mid-growth: the straight run equals the run continued from its checkpoint. 1100
-- cells: at 2 threads, with INVASIM_TEST_TEAM_STEPS=1 (src/integrate/test_hooks.hpp, set by
-- CTest and required here), every step runs in the parallel team, and the test checks that.
local n_grow = 1100
local team_steps = require("team_steps")
local function growing(seed)
  local sys, dyn = free_cells(n_grow, seed, true)
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
check(b_dyn:parallel_steps() == team_steps(200), "steps in the parallel team: " .. b_dyn:parallel_steps())
check(n_cells(straight_sys) ~= n_grow, "the tissue changed: " .. n_cells(straight_sys))
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
  local n200 = frame(200)
  local n400, ids400 = frame(400)
  check(n400 == n_cells(sys) and n200 ~= n400, string.format("frame counts %d, %d, cells %d", n200, n400, n_cells(sys)))
  -- Ids are unique, the initial cells keep theirs (0..n_grow - 1 in order among themselves), and the
  -- daughters get new ones (above every earlier id): a cell can be followed across deaths.
  local seen, born, last_initial = {}, 0, -1
  for _, id in ipairs(ids400) do
    check(not seen[id], "id " .. id .. " once")
    seen[id] = true
    if id >= n_grow then born = born + 1 else check(id > last_initial, "initial cells in order"); last_initial = id end
  end
  check(born > 0 and n400 - born < n_grow, string.format("%d daughters with new ids, %d initial cells left", born, n400 - born))
end
iv.write_file(iv.out_dir .. "/fingerprint.txt", fingerprint(straight_sys) .. "\n")
print(string.format("proliferation: all %d checks passed; %d cells after 400 steps; identical after 200 + 200 steps",
                    checks, n_cells(straight_sys)))
