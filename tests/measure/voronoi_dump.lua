-- Writes three configurations for the comparison of invasim's Voronoi measurement with voro++
-- (check_voronoi_voro.py): for each, the box, every site (kind, adipocyte, position) and what
-- sys:voronoi{} returns.
--   tissue:     the reduced system of the protocols (8 adipocytes, 400 cells) placed de-mixed
--               and compressed to phi = 0.72 as the main job does (lib/stages.lua);
--               tissue_sizes the same with adipocytes of many sizes (diameter_spread 0.25).
--   near_walls: 2 adipocytes and 100 cells of diameter 1 that diffused for a while against
--               soft walls, so that some ended beyond a wall (the tessellation clamps them to
--               it) and others close to it; also measured as the radical tessellation
--               (near_walls_radical: weights (d/2)^2, 0.25 for the cells and 1 for the vertices).
-- Usage: invasim run voronoi_dump.lua --set dir=DIR
local here = debug.getinfo(1, "S").source:match("^@(.*/)") or "./"
package.path = here .. "../../protocols/?.lua;" .. package.path
local iv = require("invasim")
local stage = require("lib.stages")
local presets = require("lib.presets")

local p = iv.params{
  dir = { "voronoi_voro", help = "directory of the written files" },
  seed = { 1, type = "integer", range = "[1, inf)" },
}
iv.make_dirs(p.dir)

local function g(x) return string.format("%.17g", x) end

-- <dir>/<name>.txt: "box lo_x hi_x lo_y hi_y lo_z hi_z", the measurement's scalars and
-- per-adipocyte lists, then "site i kind body x y z [radius]" per site (kind c or v; body
-- 0-based, -1 for a cell). The vertices of body b are the b-th run of `vertices_per_body`
-- vertex sites in index order (sys:place adds each body's vertices together, bodies in order).
-- With `radii` ({c =, v =}: the radius of every cell and every vertex), the radical
-- tessellation is measured and the radii written.
local function dump(name, sys, vertices_per_body, radii)
  local b = sys:box()
  local v = sys:voronoi{ radical = radii ~= nil }
  local lines = {
    string.format("box %s %s %s %s %s %s", g(b.lo[1]), g(b.hi[1]), g(b.lo[2]), g(b.hi[2]),
                  g(b.lo[3]), g(b.hi[3])),
  }
  for _, k in ipairs{ "A_t", "A_t_max", "cancer_adipocyte", "cancer_wall", "adipocyte_wall" } do
    lines[#lines + 1] = "scalar " .. k .. " " .. g(v[k])
  end
  for _, k in ipairs{ "adipocyte_surface", "adipocyte_wall_area" } do
    local row = { "list", k }
    for _, x in ipairs(v[k]) do row[#row + 1] = g(x) end
    lines[#lines + 1] = table.concat(row, " ")
  end
  local kind, body = {}, {}
  for _, i in ipairs(sys:group("cancer"):sites()) do kind[i], body[i] = "c", -1 end
  local vertices = sys:group("vertices"):sites()
  table.sort(vertices)
  if #vertices ~= vertices_per_body * sys:n_adipocytes() then
    error(string.format("%s: %d vertices for %d adipocytes of %d", name, #vertices,
                        sys:n_adipocytes(), vertices_per_body))
  end
  for r, i in ipairs(vertices) do kind[i], body[i] = "v", (r - 1) // vertices_per_body end
  local pos = sys:positions(sys:group("all"))
  local all = sys:group("all"):sites()
  for k, i in ipairs(all) do
    local x = pos[k]
    lines[#lines + 1] = string.format("site %d %s %d %s %s %s%s", i, kind[i], body[i], g(x[1]),
                                      g(x[2]), g(x[3]), radii and " " .. g(radii[kind[i]]) or "")
  end
  iv.write_file(p.dir .. "/" .. name .. ".txt", table.concat(lines, "\n") .. "\n")
  print(string.format("%s: %d sites, A_t = %.6f", name, #all, v.A_t))
end

-- 1. The reduced system, compressed (protocol steps 1 and 2).
local size = presets.reduced
local tissue = stage.init{ N_a = size.N_a, N_c = size.N_c, L0 = size.L0, seed = p.seed }
stage.compress(tissue, { to_phi = 0.72, progress = false })
dump("tissue", tissue.sys, tissue.vertices:size() // tissue.sys:n_adipocytes())

-- 1b. The same with adipocytes of many sizes (log-normal diameters, spread 0.25).
local sized = stage.init{ N_a = size.N_a, N_c = size.N_c, L0 = size.L0, seed = p.seed,
                         diameter_spread = 0.25 }
stage.compress(sized, { to_phi = 0.72, progress = false })
dump("tissue_sizes", sized.sys, sized.vertices:size() // sized.sys:n_adipocytes())

-- 2. Sites beyond and close to the walls: no wall force, the cells diffuse out of the slab.
local sys = iv.System{ box = { 9, 8, 8 }, periodic = { false, true, true }, seed = p.seed }
local placed = sys:place{
  adipocytes = { n = 2, diameter = 6, vertex_diameter = 2, x = { 3, 6 } },
  cells = { n = 100, diameters = { 1.0 }, x = { 0.6, 8.4 } },
}
sys:add(iv.Contacts{ alpha = 0.2 })
sys:add(iv.Walls{ eps = 0.02 })
local dyn = iv.Dynamics{ dt = 0.05 }
dyn:add(iv.Langevin{ group = placed.cells, gamma = 0.2, kT = 0.01 })
dyn:run(sys, 400)
dump("near_walls", sys, placed.vertices:size() // placed.adipocytes)
dump("near_walls_radical", sys, placed.vertices:size() // placed.adipocytes, { c = 0.5, v = 1.0 })
