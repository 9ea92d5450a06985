-- Every engine type can be built from Lua, and every kind of bad argument (unknown key,
-- wrong type, out of range, missing key, engine validation, wrong object) raises a Lua error
-- naming the key, with this file's line in front. Nothing here runs a simulation.
local iv = require("invasim")
local checks = 0

local function expect_error(pattern, f, ...)
  local ok, err = pcall(f, ...)
  assert(not ok, "expected an error matching " .. pattern)
  assert(type(err) == "string" and err:find(pattern), "wrong message: " .. tostring(err))
  assert(err:find("^engine_api%.lua:%d+: "), "no location: " .. err)
  checks = checks + 1
end
local function check(condition, message)
  if not condition then error("check failed" .. (message and (": " .. message) or ""), 2) end
  checks = checks + 1
end

-- System
local sys = iv.System{ box = {20, 14, 14}, periodic = {false, true, true}, seed = 5 }
check(tostring(sys):find("^System%(0 sites"), tostring(sys))
check(sys:n_sites() == 0 and sys:n_adipocytes() == 0 and sys:step() == 0 and sys:time() == 0)
local box = sys:box()
check(box.lengths[1] == 20 and box.lo[2] == 0 and box.hi[3] == 14 and box.periodic[1] == false)
expect_error("System: missing required key 'box' %(a list of 3 numbers%)", iv.System, {})
-- A misspelt required key is named with the one it should be (lists, bound objects, keywords).
expect_error("System: missing required key 'box' %(a list of 3 numbers%); unknown key 'bxo' " ..
             "%(did you mean 'box'%?%)", iv.System, { bxo = { 10, 10, 10 } })
expect_error("System: unknown key 'sed' %(did you mean 'seed'%?%); valid keys: box, periodic, seed",
             iv.System, { box = {1, 1, 1}, sed = 1 })
expect_error("System: key 'box' must be a list of 3 numbers, got a table of length 2",
             iv.System, { box = {1, 1} })
expect_error("System: key 'box%[2%]' = 0 is out of range %(must be > 0%)", iv.System, { box = {1, 0, 1} })
expect_error("System: key 'seed' must be an integer, got string", iv.System, { box = {1, 1, 1}, seed = "1" })
expect_error("System: key 'periodic' must be a list of 3 booleans", iv.System,
             { box = {1, 1, 1}, periodic = {true} })
-- The reported line is the line of the call.
local ok, err = pcall(iv.System, { box = 3 }); local line = debug.getinfo(1, "l").currentline
check(not ok and err:find("^engine_api%.lua:" .. line .. ": System: key 'box' must be a list of 3 numbers, got 3"), err)

-- Placement
local placed = sys:place{ cells = { n = 20, diameters = {0.9, 1.1}, x = {1, 4} },
                          adipocytes = { n = 2, diameter = 6, vertex_diameter = 2, shape_param = 1.1, x = {7, 17} } }
check(placed.cells:size() == 20 and placed.vertices:size() == 84 and placed.adipocytes == 2)
check(sys:n_sites() == 104 and sys:n_adipocytes() == 2)
check(placed.cells:sites()[1] == 84 and placed.vertices:sites()[1] == 0, "site indices are 0-based")
expect_error("place.cells: unknown key 'diamters' %(did you mean 'diameters'%?%)", sys.place, sys,
             { cells = { n = 1, x = {1, 2}, diamters = {1} } })
expect_error("place.cells: missing required key 'x'", sys.place, sys, { cells = { n = 1 } })
expect_error("place.cells: key 'n' = %-1 is out of range %(must be in %[0, 2147483647%]%)", sys.place, sys,
             { cells = { n = -1, x = {1, 2} } })
expect_error("place.cells: key 'diameters%[2%]' must be a number > 0, got %-1", sys.place, sys,
             { cells = { n = 1, x = {1, 2}, diameters = {1, -1} } })
expect_error("place.adipocytes: key 'shape_param' = 0.5 is out of range %(must be >= 1%)", sys.place, sys,
             { adipocytes = { n = 1, x = {7, 17}, shape_param = 0.5 } })
expect_error("place: unknown key 'cell' %(did you mean 'cells'%?%)", sys.place, sys, { cell = {} })
-- Adipocytes of many sizes: a list in turn or a log-normal spread, not both.
expect_error("place.adipocytes: key 'spread' = %-0.1 is out of range %(must be >= 0%)", sys.place, sys,
             { adipocytes = { n = 1, x = {7, 17}, spread = -0.1 } })
expect_error("place: adipocyte placement: give the diameters as a list or as a spread, not both", sys.place, sys,
             { adipocytes = { n = 1, x = {7, 17}, diameters = {5, 7}, spread = 0.1 } })
do
  local big = iv.System{ box = { 60, 60, 60 }, periodic = { false, true, true }, seed = 3 }
  big:place{ adipocytes = { n = 4, diameters = { 5, 8 }, x = { 5, 55 } } }
  local v = big:adipocytes()
  local function same(a, b) return math.abs(a - b) <= 1e-9 * b end  -- (rotated meshes: rounding)
  check(#v == 4 and v[1].ref_volume < 0.5 * v[2].ref_volume and same(v[1].ref_volume, v[3].ref_volume)
        and same(v[2].ref_volume, v[4].ref_volume), "adipocytes' sizes in turn from the list")
end
expect_error("place: cancer%-cell placement: only", sys.place, sys,
             { cells = { n = 5000, x = {1, 2}, max_attempts = 10 } })
-- Cells at given positions (a start from another program): placed as given, n follows.
do
  local given = iv.System{ box = { 10, 10, 10 }, seed = 1 }
  local at = given:place{ cells = { positions = { { 1, 2, 3 }, { 1.5, 2, 3 }, { 9, 12.5, -0.5 } },
                                    diameters = { 0.9, 1.1, 1.0 } } }
  local r = given:positions(at.cells)
  check(at.cells:size() == 3 and r[2][1] == 1.5 and r[3][2] == 2.5 and r[3][3] == 9.5,
        "cells placed where given, wrapped on the periodic axes")
end
expect_error("place.cells: key 'positions%[2%]' must be a list of 3 numbers, got a table of length 2",
             sys.place, sys, { cells = { positions = { { 1, 2, 3 }, { 1, 2 } } } })
expect_error("place.cells: key 'diameters%[1%]' must be a number > 0, got nan", sys.place, sys,
             { cells = { positions = { { 1, 2, 3 } }, diameters = { 0 / 0 } } })
expect_error("place.cells: key 'positions%[1%]%[3%]' must be a finite number, got nan", sys.place, sys,
             { cells = { positions = { { 1, 2, 0 / 0 } } } })
expect_error("place: cells.x goes with random placement; with positions the cells are placed as given",
             sys.place, sys, { cells = { positions = { { 1, 2, 3 } }, x = { 1, 2 } } })
expect_error("place: cancer%-cell placement: n = 2 for 1 given positions", sys.place, sys,
             { cells = { n = 2, positions = { { 1, 2, 3 } } } })
expect_error("place: cancer%-cell placement: position 1 has x = 25, outside the walls %[0, 20%]", sys.place, sys,
             { cells = { positions = { { 25, 2, 3 } } } })

-- Groups
local cancer, vertices = sys:group("cancer"), sys:group("vertices")
check(sys:group("all"):size() == sys:n_sites() and cancer:name() == "cancer")
check(cancer:size() >= 20 and vertices:size() == 84)
expect_error("group: unknown group 'cancr' %(did you mean 'cancer'%?%); groups: all, cancer, vertices",
             sys.group, sys, "cancr")
expect_error("bad argument #1 to 'group' %(string expected, got number%)", function() return sys:group(1) end)
expect_error("for a method call write obj:method", function() return sys.n_sites() end)
expect_error("System has no method or field 'nsites' %(did you mean 'n_sites'%?%)", function() return sys:nsites() end)

-- Forces
local contacts = iv.Contacts{ alpha = 0.2, beta = 1e-2, eps_cc = 1, eps_cv = 1, eps_vv = 1, skin = 0.3 }
local walls = iv.Walls{ eps = 1, left = true, right = true }
local shape = iv.Shape{ eps_v = 1e3, eps_a = 1 }
local tethers = iv.Tethers{ K = 1e-2 }
check(contacts:params().beta == 1e-2 and shape:params().eps_v == 1e3 and tethers:K() == 1e-2)
check(iv.Contacts{}:params().beta == 0, "Contacts default: purely repulsive")
expect_error("Contacts: key 'alpha' must be a number, got string", iv.Contacts, { alpha = "x" })
expect_error("Contacts: key 'eps_cc' = 0 is out of range %(must be > 0%)", iv.Contacts, { eps_cc = 0 })
expect_error("Contacts: cohesion: beta = 0.3 must be smaller than alpha = 0.2", iv.Contacts, { beta = 0.3 })
-- Cancer-adipocyte adhesion: off by default, its own range, the same rule as cohesion.
check(iv.Contacts{}:params().beta_cv == 0 and iv.Contacts.defaults.alpha_cv == 0.2, "Contacts default: no adhesion")
local adhesive = iv.Contacts{ alpha_cv = 0.3, beta_cv = 0.05 }
check(adhesive:params().alpha_cv == 0.3 and adhesive:params().beta_cv == 0.05 and adhesive:params().beta == 0)
expect_error("Contacts: adhesion: beta_cv = 0.2 must be smaller than alpha_cv = 0.2", iv.Contacts, { beta_cv = 0.2 })
expect_error("Contacts: key 'beta_cv' = %-1 is out of range %(must be >= 0%)", iv.Contacts, { beta_cv = -1 })
expect_error("Walls: key 'left' must be a boolean", iv.Walls, { left = 1 })
expect_error("Walls: unknown key 'eps_w' %(did you mean 'eps'%?%)", iv.Walls, { eps_w = 1 })
expect_error("Shape: missing required key 'eps_a' %(a number%)", iv.Shape, { eps_v = 1 })
expect_error("Tethers: key 'K' = %-1 is out of range %(must be >= 0%)", iv.Tethers, { K = -1 })
-- A method taking a bare number is checked by the engine: NaN (printed "nan" whatever its sign
-- bit) and infinity are refused as well as negatives.
expect_error("set_K: K_ecm = nan must be a number >= 0", tethers.set_K, tethers, 0 / 0)
expect_error("set_K: K_ecm = inf must be finite", tethers.set_K, tethers, math.huge)
expect_error("set_K: K_ecm = %-1 must be >= 0", tethers.set_K, tethers, -1)
expect_error("connect: not in a System; add the tethers to a System first", tethers.connect, tethers, {})
for _, f in ipairs{ walls, contacts, shape, tethers } do check(sys:add(f) == f) end
check(#sys:forces() == 4 and tostring(sys:forces()[2]):find("^Contacts") ~= nil, "forces list")
expect_error("add: this Walls is already in the System", sys.add, sys, walls)
expect_error("add: this Contacts is already in another System", iv.System{ box = {5, 5, 5} }.add,
             iv.System{ box = {5, 5, 5} }, contacts)
expect_error("bad argument #1 to 'add' %(force %(Contacts, Walls, Shape or Tethers%) expected, got number%)",
             function() return sys:add(5) end)
local d_c = tethers:connect{ mean_degree = 1 }
check(d_c > 0 and tethers:count() == 1, "2 adipocytes, mean degree 1: one tether")
tethers:heterogeneity{ lambda = 0.3 }
expect_error("heterogeneity: key 'lambda' = 2 is out of range %(must be in %[0, 1%]%)",
             tethers.heterogeneity, tethers, { lambda = 2 })
expect_error("connect: key 'mean_degree' = 0 is out of range", tethers.connect, tethers, { mean_degree = 0 })
local energy = sys:compute()
check(energy.total == energy.contact + energy.wall + energy.shape + energy.tether and #energy.virial == 3)

-- Methods and Dynamics
local damped = iv.Damped{ group = vertices, gamma = 0.2 }
local langevin = iv.Langevin{ group = cancer, gamma = 0.2, kT = 1e-3 }
local active = iv.Active{ group = cancer, gamma = 0.2, f0 = 0.05, tau_p = 25, kT = 0 }
check(damped:kind() == "Damped" and langevin:params().kT == 1e-3 and active:params().tau_p == 25)
check(active:group():size() == cancer:size())
expect_error("Langevin: missing required key 'kT' %(a number%)", iv.Langevin, { group = cancer })
expect_error("Damped: missing required key 'group' %(a Group from sys:group%(name%) or sys:place{...}%)",
             iv.Damped, {})
expect_error("Active: missing required key 'group' %(a Group from sys:group%(name%) or " ..
             "sys:place{...}%); unknown key 'grup' %(did you mean 'group'%?%)", iv.Active,
             { grup = cancer, f0 = 0.05, tau_p = 25 })
expect_error("Damped: key 'group' must be a Group from sys:group%(name%) or sys:place{...}, got table",
             iv.Damped, { group = {1, 2} })
expect_error("Active: key 'tau_p' = %-1 is out of range %(must be >= 0%)", iv.Active,
             { group = cancer, f0 = 1, tau_p = -1 })
expect_error("Active: unknown key 'taup' %(did you mean 'tau_p'%?%)", iv.Active,
             { group = cancer, f0 = 1, tau_p = 1, taup = 1 })
local dyn = iv.Dynamics{ dt = 0.05 }
check(dyn:add(damped) == damped and dyn:add(langevin) == langevin and dyn:dt() == 0.05)
check(#dyn:methods() == 2 and dyn:wall_state() == nil)
expect_error("add: this Langevin method is already in the Dynamics", dyn.add, dyn, langevin)
expect_error("Dynamics: key 'dt' = %-1 is out of range %(must be > 0%)", iv.Dynamics, { dt = -1 })
expect_error("Dynamics: key 'dt' must be a finite number, got inf", iv.Dynamics, { dt = math.huge })
expect_error("pressure_wall: missing required key 'P' %(a number%)", dyn.pressure_wall, dyn, {})
expect_error("pressure_wall: key 'walls' must be a Walls force, got Contacts", dyn.pressure_wall, dyn,
             { P = 1e-3, walls = contacts })
expect_error("run: a callback needs key 'every'", dyn.run, dyn, sys, 1, { callback = print })
expect_error("run: key 'callback' must be a function, got number", dyn.run, dyn, sys, 1,
             { every = 1, callback = 1 })
expect_error("run: key 'every' = 0 is out of range %(must be >= 1%)", dyn.run, dyn, sys, 1, { every = 0 })
expect_error("bad argument #1 to 'run' %(System expected, got nil%)", function() return dyn:run(nil, 1) end)
local other = iv.System{ box = {10, 10, 10} }
expect_error("run: Damped: group 'vertices' belongs to another System", dyn.run, dyn, other, 1)
expect_error("pressure_wall: key 'kT' = %-1 is out of range %(must be >= 0%)", dyn.pressure_wall, dyn,
             { P = 1e-3, kT = -1 })
expect_error("set_wall_kT: this Dynamics has no pressure wall", dyn.set_wall_kT, dyn, 1e-3)
dyn:pressure_wall{ P = 1e-3, mass = 1, gamma = 0.2, walls = walls }
check(dyn:wall_state().P == 1e-3 and dyn:wall_state().kT == 0)
dyn:set_wall_kT(2e-4)
check(dyn:wall_state().kT == 2e-4)
expect_error("set_wall_kT: kT = %-1 must be >= 0", dyn.set_wall_kT, dyn, -1)
dyn:pressure_wall{ P = 1e-3, kT = 1e-4, walls = walls }
check(dyn:wall_state().kT == 1e-4)
local fresh = iv.System{ box = {10, 10, 10} }
local lonely = iv.Dynamics{}
lonely:pressure_wall{ P = 1 }
expect_error("run: the pressure wall needs a Walls force in the System", lonely.run, lonely, fresh, 1)
check(dyn:run(sys, 0) == 0 and sys:step() == 0)

-- Ramps and setters
local ramp = iv.ramp{ from = 0, to = 1e-2, steps = 100 }
check(tostring(ramp) == "Ramp(from=0, to=0.01, steps=100)", tostring(ramp))
check(ramp:value(0) == 0 and ramp:value(50) == 5e-3 and ramp:value(500) == 1e-2)
expect_error("ramp: missing required key 'steps'", iv.ramp, { from = 0, to = 1 })
expect_error("ramp: key 'steps' = 0 is out of range %(must be >= 1%)", iv.ramp, { from = 0, to = 1, steps = 0 })
expect_error("ramp: missing required key 'from' %(a number%); unknown key 'form' %(did you mean 'from'%?%)", iv.ramp, { form = 0, to = 1, steps = 1 })
expect_error("ramp: a ramp from 1e%+308 to %-1e%+308 spans more than the largest number", iv.ramp,
             { from = 1e308, to = -1e308, steps = 10 })
check(iv.ramp{ from = 1e308, to = 0, steps = 10 }:value(5) == 5e307)
expect_error("Langevin: key 'kT': ramp end %-1 is out of range %(must be >= 0%)", iv.Langevin,
             { group = cancer, kT = iv.ramp{ from = -1, to = 1, steps = 10 } })
expect_error("Langevin: key 'kT' must be a number or an invasim.ramp{}, got Group", iv.Langevin,
             { group = cancer, kT = cancer })
check(iv.Langevin{ group = cancer, kT = ramp }:params().kT == 0)
check(iv.Active{ group = cancer, f0 = ramp, tau_p = math.huge, randomize = false }:params().tau_p == math.huge)
langevin:set{ kT = 2e-3, gamma = 0.3 }
check(langevin:params().kT == 2e-3 and langevin:params().gamma == 0.3)
langevin:set{ gamma = 0.2, kT = 1e-3 }
expect_error("Langevin:set: unknown key 'f0'", langevin.set, langevin, { f0 = 1 })
expect_error("Damped:set: unknown key 'kT'", damped.set, damped, { kT = 1 })
expect_error("Active:set: key 'tau_p' = %-2 is out of range", active.set, active, { tau_p = -2 })
contacts:set{ beta = 5e-3 }
check(contacts:params().beta == 5e-3 and contacts:params().alpha == 0.2)
expect_error("Contacts:set: cohesion: beta = 0.3 must be smaller than alpha", contacts.set, contacts, { beta = 0.3 })
check(contacts:params().beta == 5e-3)
contacts:set{ beta = 1e-2 }
expect_error("set_pressure: this Dynamics has no pressure wall", iv.Dynamics{}.set_pressure, iv.Dynamics{}, 1)
expect_error("set_dt: dt = 0 must be > 0", dyn.set_dt, dyn, 0)
expect_error("set_dt: dt = inf must be finite", dyn.set_dt, dyn, math.huge)
expect_error("set_dt: dt = nan must be a number > 0", dyn.set_dt, dyn, 0 / 0)
check(dyn:dt() == 0.05)
check(type(iv.clock()) == "number")
check(#sys:positions(cancer) == cancer:size() and #sys:positions() == sys:n_sites())
check(#sys:adipocytes() == sys:n_adipocytes() and sys:adipocytes()[1].ref_volume > 0)

-- Measurements and files
local vor = sys:voronoi()
check(vor.A_t >= 0 and vor.A_t_max > 0 and math.abs(vor.A_ratio - vor.A_t / vor.A_t_max) < 1e-12)
check(#vor.adipocyte_surface == sys:n_adipocytes() and #vor.local_phi_a == sys:n_adipocytes())
do  -- A_t^max = 2 L_y L_z + sum S_i; the wall faces of the adipocytes are reported apart
  local L = sys:box().lengths
  local s_sum, w_sum = 0.0, 0.0
  for i = 1, sys:n_adipocytes() do
    s_sum, w_sum = s_sum + vor.adipocyte_surface[i], w_sum + vor.adipocyte_wall_area[i]
  end
  check(math.abs(vor.A_t_max - (2 * L[2] * L[3] + s_sum)) < 1e-9 * vor.A_t_max)
  check(vor.adipocyte_wall >= 0 and math.abs(vor.adipocyte_wall - w_sum) < 1e-9 * (1 + w_sum))
end
check(sys:voronoi{ radical = true }.A_t_max > 0)
expect_error("voronoi: unknown key 'radial' %(did you mean 'radical'%?%)", sys.voronoi, sys, { radial = true })
check(#sys:shape_parameters() == sys:n_adipocytes())
check(#sys:slices{ per_body = 3 } >= 3 * sys:n_adipocytes())
expect_error("slices: key 'per_body' = 0 is out of range %(must be in %[1, 8192%]%)", sys.slices, sys, { per_body = 0 })
local h = iv.histogram({ 1, 2, 2, 3, 9 }, { lo = 0, hi = 4, bins = 4 })
check(h.counts[3] == 2 and h.above == 1 and #h.edges == 5)
expect_error("histogram: hi = 0 must be greater than lo = 1", iv.histogram, { 1 }, { lo = 1, hi = 0 })
expect_error("histogram: entry %[2%] must be a number, got string", iv.histogram, { 1, "x" }, { lo = 0, hi = 1 })
-- 1..8: rho(1) = 0.625, rho(2) = 0.274; the cap (W <= floor((16/3 - 1)/2) = 2) stops the sum at
-- tau_int(2) = 1.399 before W >= 5 tau_int(W): unresolved.
local me = iv.mean_error({ 1, 2, 3, 4, 5, 6, 7, 8 })
check(me.mean == 4.5 and me.n == 8 and me.window == 2 and me.resolved == false and me.tau_int > 0.5)
-- C_F = 2 x 1.399 x 5.25 / (1 - 5/8) = 39.17, Var = 5.25 + C_F/8 = 10.15: error sqrt(C_F/8) = 2.213
check(math.abs(me.error - 2.2128) < 1e-3, me.error)
local flat = iv.mean_error({ 2, 2, 2, 2 }, { fraction = 0.5 })
check(flat.n == 2 and flat.error == 0 and flat.resolved == true)
expect_error("mean_error: key 'fraction' = 2 is out of range", iv.mean_error, { 1, 2 }, { fraction = 2 })
expect_error("mean_error: unknown key 'min_blocks'", iv.mean_error, { 1, 2 }, { min_blocks = 4 })
local corr = iv.Correlator{ group = cancer, interval = 0.05, lags = 10 }
check(tostring(corr):find("^Correlator%(group 'cancer'"), tostring(corr))
corr:sample(sys)
check(corr:samples() == 1 and corr:result().columns.fs[1] == 1 and corr:result().columns.msd[1] == 0 and corr:tau_d() == nil)
expect_error("Correlator: missing required key 'interval'", iv.Correlator, { group = cancer })
expect_error("Correlator: key 'fs_average' must be one of: isotropic, yz", iv.Correlator,
             { group = cancer, interval = 1, fs_average = "xy" })
expect_error("sample: group 'cancer' belongs to another System", corr.sample, corr, iv.System{ box = {10, 10, 10} })
expect_error("Snapshots: missing required key 'dir'", iv.Snapshots, {})
-- trajectory.xyz appends a frame per write; a new writer in the directory (a resumed run)
-- first drops the frames at and after its own first step.
local trajectory_dir = iv.out_dir .. "/trajectory"
iv.remove_path(trajectory_dir)
local function trajectory_writer()
  return iv.Snapshots{ dir = trajectory_dir, trajectory = true, cells_xyz = false,
                       spheres_vtp = false, adipocytes_vtp = false }
end
local function trajectory_frames()
  local f = assert(io.open(trajectory_dir .. "/trajectory.xyz"))
  local _, frames = f:read("a"):gsub("Step=", "")
  f:close()
  return frames
end
local writer = trajectory_writer()
writer:write(sys)
writer:write(sys)
check(trajectory_frames() == 2, "two frames appended")
trajectory_writer():write(sys)
check(trajectory_frames() == 1, "a new writer replaces the frames from its first step on")
expect_error("bad argument #2 to '.-' %(string expected, got no value%)", iv.write_file, "x")

-- Fire, compress, rescale
local fire = iv.Fire{ ftol = 1e-8, dt = 0.05, dt_max = 0.5, max_steps = 1e6 }
check(tostring(fire):find("^Fire%(ftol=1e%-08"), tostring(fire))
expect_error("Fire: key 'max_steps' must be an integer, got 0.5", iv.Fire, { max_steps = 0.5 })
expect_error("Fire: unknown key 'ftoll' %(did you mean 'ftol'%?%)", iv.Fire, { ftoll = 1 })
expect_error("minimize: the Dynamics has no pressure wall", fire.minimize, fire, sys, iv.Dynamics{})
expect_error("compress: missing required key 'to_phi' %(a number%)", iv.compress, sys, {})
expect_error("compress: key 'to_phi' = 2 is out of range %(must be in %(0, 1%)%)", iv.compress, sys, { to_phi = 2 })
expect_error("compress: key 'to_phi' = 1 is out of range %(must be in %(0, 1%)%)", iv.compress, sys, { to_phi = 1 })
expect_error("compress: key 'step' = 0 is out of range %(must be in %(0, 1%)%)", iv.compress, sys, { to_phi = 0.5, step = 0 })
expect_error("mean_error: key 'fraction' = 0 is out of range %(must be in %(0, 1%]%)", iv.mean_error, { 1, 2 }, { fraction = 0 })
expect_error("mean_error: values%[2%] = nan is not a finite number", iv.mean_error, { 1, 0 / 0, 3 })
expect_error("histogram: hi = 1e%+308 must be greater than lo = %-1e%+308, by a finite width",
             iv.histogram, { 1 }, { lo = -1e308, hi = 1e308 })
check(iv.histogram({ 0 / 0, math.huge, -math.huge, 1 }, { lo = 0, hi = 2, bins = 2 }).invalid == 3)
expect_error("compress: the packing fraction is already", iv.compress, sys, { to_phi = 0.01 })
expect_error("compress: key 'progress' must be a Progress, got table", iv.compress, sys, { to_phi = 0.5, progress = {} })
expect_error("compress: key 'continue_from' must be a table, got number", iv.compress, sys,
             { to_phi = 0.5, continue_from = 3 })
expect_error("compress: continue_from: missing required key 'fire_steps'", iv.compress, sys,
             { to_phi = 0.5, continue_from = { steps = 1 } })
expect_error("compress: continue_from: unknown key 'phi'", iv.compress, sys,
             { to_phi = 0.5, continue_from = { steps = 1, fire_steps = 0, converged = true, max_force = 0, phi = 0.1 } })
expect_error("rescale: missing required key 'phi_a'", iv.rescale, sys, {})
expect_error("set_velocities: missing required key 'kT'", sys.set_velocities, sys, {})
expect_error("temperature: group 'cancer' belongs to another System", other.temperature, other, cancer)

-- A collected System leaves its objects usable but detached.
local orphan = iv.System{ box = {10, 10, 10} }
local orphan_group = orphan:group("all")
orphan = nil
collectgarbage(); collectgarbage()
expect_error("Active: group 'all': its System no longer exists", iv.Active, { group = orphan_group, f0 = 1, tau_p = 1 })

-- A defaults table iterates by raw access, whatever the script did to the global `next`.
do
  local saved_next, n = next, 0
  next = nil
  for _ in pairs(iv.Contacts.defaults) do n = n + 1 end
  next = saved_next
  check(n == 8, "pairs(iv.Contacts.defaults) gave " .. n .. " keys")
end

-- Keys holding bound objects (kw_object): absent when required, and of the wrong type.
expect_error("save_checkpoint: missing required key 'system' %(a System%)", iv.save_checkpoint,
             "unused.ckpt", { extra = "" })
expect_error("save_checkpoint: key 'tethers' must be a Tethers, got Contacts", iv.save_checkpoint,
             "unused.ckpt", { system = sys, tethers = iv.Contacts{} })
expect_error("run: key 'progress' must be a Progress, got string", iv.Dynamics{}.run, iv.Dynamics{},
             sys, 1, { progress = "p" })
-- A Progress goes forwards: a step before the last one would give a negative rate and ETA.
local progress = iv.Progress{ total = 10, start = 2, live = false, every_seconds = 1e9 }
expect_error("update: step 1 is before the last one, 2", progress.update, progress, 1)
progress:update(5)
expect_error("update: step 4 is before the last one, 5", progress.update, progress, 4)
progress:update(5)
-- A value after the arguments a function takes is refused, as an unknown key is (trailing
-- nils pass): hand-written bindings and the method<> adapters alike.
expect_error("bad argument #1 to 'compute' %(no value expected, got table%)", sys.compute, sys, { per_site = true })
-- Getters, params() and the other queries without arguments refuse one too.
expect_error("bad argument #1 to 'n_sites' %(no value expected, got string%)", sys.n_sites, sys, "junk")
expect_error("bad argument #1 to 'box' %(no value expected, got table%)", sys.box, sys, {})
expect_error("bad argument #1 to 'packing' %(no value expected, got number%)", sys.packing, sys, 1)
expect_error("bad argument #1 to 'forces' %(no value expected, got number%)", sys.forces, sys, 1)
expect_error("bad argument #1 to 'adipocytes' %(no value expected, got number%)", sys.adipocytes, sys, 1)
local loose_contacts = iv.Contacts{}
expect_error("bad argument #1 to 'params' %(no value expected, got number%)", loose_contacts.params, loose_contacts, 1)
expect_error("bad argument #2 to 'group' %(no value expected, got table%)", sys.group, sys, "cancer", {})
expect_error("bad argument #2 to 'positions' %(no value expected, got table%)", sys.positions, sys,
             sys:group("cancer"), { unwrapped = true })
expect_error("bad argument #2 to 'set_dt' %(no value expected, got number%)", iv.Dynamics{}.set_dt,
             iv.Dynamics{}, 0.01, 5)
check(sys:compute(nil).total ~= nil and #sys:positions(nil, nil) == sys:n_sites(), "trailing nils pass")
-- The contacts' parameters in a checkpoint: restored where given, kept where not.
do
  local function tissue(beta)
    local s = iv.System{ box = { 10, 10, 10 }, seed = 1 }
    s:place{ cells = { positions = { { 1, 2, 3 }, { 5, 5, 5 } } } }
    return s, s:add(iv.Contacts{ beta = beta })
  end
  local path = iv.out_dir .. "/contacts.ckpt"
  iv.make_dirs(iv.out_dir)
  local first, first_contacts = tissue(0.01)
  first_contacts:set{ beta = 0.05 }
  iv.save_checkpoint(path, { system = first, contacts = first_contacts })
  local again, again_contacts = tissue(0.01)
  iv.load_checkpoint(path, { system = again })
  check(again_contacts:params().beta == 0.01, "contacts not given: their own parameters")
  iv.load_checkpoint(path, { system = again, contacts = again_contacts })
  check(again_contacts:params().beta == 0.05, "contacts given: the checkpoint's parameters")
  expect_error("checkpoint: key 'contacts' must be the Contacts force of its System", iv.load_checkpoint,
               path, { system = again, contacts = first_contacts })
end

print("engine_api: all " .. checks .. " checks passed")
