-- invasim's side of cross_check_lammps.sh: thermal cancer cells, fully periodic, started from
-- a LAMMPS "atomic" data file (`data`: the very file LAMMPS reads; types 1/2 = diameters
-- 0.9/1.1, as bench_engine lammps-data writes them), placed where it says with
-- sys:place{cells = {positions =, diameters =}}; contacts alpha = 0.2, beta.
-- mode = "run": Langevin (gamma = 0.2, kT) with dt = 0.05; after eq_steps, `steps` steps of
--   production with, every `every` steps, the contact energy, kinetic temperature and virial
--   trace (thermo.csv: step, time, U, kT, W = sum_a W_aa), the wrapped positions (positions.bin:
--   float64 x y z per cell, frame after frame) and a sample of invasim's own Correlator
--   (msd.csv); every snap_every steps an XYZ snapshot (snapshots/, for g(r)); info.json.
-- mode = "static": the state as placed (NAME.start.bin: float64 x y z diameter per cell), its
--   contact energy and virial trace (NAME.invasim.json) and the positions after one step from
--   rest without damping or noise (NAME.step.bin: float64 x y z), whence F = 2 (x1 - x0) / dt^2.
--   invasim run cross_check_lammps.lua --out DIR --set data=data.1500 --set beta=0.01 --set seed=3
local iv = require("invasim")

local p = iv.params{
  data = { "data.1500", help = "LAMMPS data file of the start (atom_style atomic)" },
  mode = { "run", choices = { "run", "static" }, help = "Langevin run or one-state check" },
  name = { "state", help = "static: prefix of the output files in --out" },
  beta = { 0.0, range = "[0, 0.2)", help = "cohesion depth (0: repulsive)" },
  kT = { 1e-3, range = "[0, inf)", help = "bath temperature" },
  seed = { 1, range = "[0, inf)", help = "noise seed" },
  eq_steps = { 4000, range = "[0, inf)", type = "integer", help = "steps before measuring" },
  steps = { 40000, range = "[1, inf)", type = "integer", help = "production steps" },
  every = { 20, range = "[1, inf)", type = "integer", help = "steps between samples" },
  snap_every = { 1000, range = "[1, inf)", type = "integer", help = "steps between XYZ snapshots" },
  lags = { 101, range = "[2, inf)", type = "integer", help = "correlator lags (of every steps)" },
  origin_every = { 5, range = "[1, inf)", type = "integer", help = "samples between correlator origins" },
}
local out = assert(iv.out_dir, "give --out DIR")
local DIAMETER = { 0.9, 1.1 }  -- by atom type
local dt = 0.05

-- The data file: box (header lines "lo hi xlo xhi"), masses by type ("Masses"), and
-- "id type x y z" per atom ("Atoms"; ids 1 .. n in any order). No velocities: both programs
-- start from rest.
local function read_data(path)
  local box, mass, atoms, n, section, title = {}, {}, {}, nil, nil, true
  for line in io.lines(path) do
    local w = {}
    for word in line:gsub("#.*", ""):gmatch("%S+") do w[#w + 1] = word end
    if title then
      title = false  -- the first line is a title
    elseif w[1] == "Masses" or w[1] == "Atoms" or w[1] == "Velocities" then
      assert(w[1] ~= "Velocities", path .. ": velocities are not read")
      section = w[1]
    elseif section == nil and w[2] == "atoms" then
      n = math.tointeger(tonumber(w[1]))
    elseif section == nil and #w == 4 and w[3]:match("^[xyz]lo$") then
      box[w[3]:sub(1, 1)] = { tonumber(w[1]), tonumber(w[2]) }
    elseif section == "Masses" and #w == 2 then
      mass[math.tointeger(tonumber(w[1]))] = tonumber(w[2])
    elseif section == "Atoms" and #w >= 5 then
      atoms[math.tointeger(tonumber(w[1]))] = { type = math.tointeger(tonumber(w[2])),
        x = { tonumber(w[3]), tonumber(w[4]), tonumber(w[5]) } }
    end
  end
  assert(n and box.x and box.y and box.z and mass[1], path .. ": no atom count, box or masses")
  for id = 1, n do assert(atoms[id], path .. ": no atom " .. id) end
  return n, { box.x, box.y, box.z }, mass, atoms
end

-- A System of the data file's box (shifted to the origin) with its cells, in id order.
local n, bounds, mass, atoms = read_data(p.data)
local lengths, positions, diameters = {}, {}, {}
for a = 1, 3 do lengths[a] = bounds[a][2] - bounds[a][1] end
for id = 1, n do
  local at = atoms[id]
  assert(DIAMETER[at.type] and mass[at.type] == mass[1], "types 1 and 2 of one mass expected")
  positions[id] = { at.x[1] - bounds[1][1], at.x[2] - bounds[2][1], at.x[3] - bounds[3][1] }
  diameters[id] = DIAMETER[at.type]
end
local sys = iv.System{ box = lengths, periodic = { true, true, true }, seed = p.seed }
local cells = sys:place{ cells = { positions = positions, diameters = diameters } }.cells
sys:set_mass{ group = cells, mass = mass[1] }
sys:add(iv.Contacts{ alpha = 0.2, beta = p.beta })

-- float64 rows of a list of {x, y, z} (and optionally a fourth column), little-endian.
local function pack_rows(rows, extra)
  local parts = {}
  for i, r in ipairs(rows) do
    parts[i] = extra and string.pack("<dddd", r[1], r[2], r[3], extra[i])
                      or string.pack("<ddd", r[1], r[2], r[3])
  end
  return table.concat(parts)
end

iv.make_dirs(out)
if p.mode == "static" then
  local base = out .. "/" .. p.name
  iv.write_file(base .. ".start.bin", pack_rows(sys:positions(cells), diameters))
  local e = sys:compute()
  iv.write_file(base .. ".invasim.json",
                iv.json_encode{ U = e.contact, W = e.virial[1] + e.virial[2] + e.virial[3] })
  local dyn = iv.Dynamics{ dt = dt }
  dyn:add(iv.Damped{ group = cells, gamma = 0 })
  dyn:run(sys, 1)
  iv.write_file(base .. ".step.bin", pack_rows(sys:positions(cells)))
  iv.stop()
end

iv.make_dirs(out .. "/snapshots")
local dyn = iv.Dynamics{ dt = dt }
dyn:add(iv.Langevin{ group = cells, gamma = 0.2, kT = p.kT })
dyn:run(sys, p.eq_steps)

local thermo = assert(io.open(out .. "/thermo.csv", "w"))
thermo:write("step,time,U,kT,W\n")
local traj = assert(io.open(out .. "/positions.bin", "wb"))
local correlator = iv.Correlator{ group = cells, interval = p.every * dt, lags = p.lags,
                                  origin_every = p.origin_every, velocity = false,
                                  orientation = false, position = true }
local sim = iv.Simulation{ system = sys, dynamics = dyn }
sim:sample(correlator, { every = p.every })
sim:observe(function(step, time)
  local e = sys:compute()
  thermo:write(string.format("%d,%.17g,%.17g,%.17g,%.17g\n", step, time, e.contact,
                             sys:temperature(cells), e.virial[1] + e.virial[2] + e.virial[3]))
  traj:write(pack_rows(sys:positions(cells)))
end, { every = p.every })
sim:snapshots(iv.Snapshots{ dir = out .. "/snapshots", spheres_vtp = false, adipocytes_vtp = false },
              { every = p.snap_every })
local clock = iv.clock()
sim:run(p.steps)
thermo:close()
traj:close()

local c = correlator:result().columns
local lines = { "t,origins,msd,fs" }
for k = 1, #c.t do
  lines[#lines + 1] = string.format("%.17g,%d,%.17g,%.17g", c.t[k], c.origins[k], c.msd[k], c.fs[k])
end
iv.write_file(out .. "/msd.csv", table.concat(lines, "\n") .. "\n")
iv.write_file(out .. "/info.json", iv.json_encode{ N = sys:n_sites(), volume = sys:box().volume,
  box = sys:box().lengths, kT = p.kT, beta = p.beta, seed = p.seed, eq_steps = p.eq_steps,
  steps = p.steps, every = p.every, production_seconds = iv.clock() - clock })
