-- Test: a second quench with unchanged options (tethered.lua's "equilibrate") continues the
-- trajectory exactly: quench(n) + quench(m) gives the state of quench(n + m), for active,
-- passive and damped-vertex motion. The second quench sets the time step and the piston's kT
-- it already has; preparing the forces again for that would re-evaluate the next step's
-- damping with the full-step velocity, and the trajectories would part (~1e-5 sigma).
package.path = "../../protocols/?.lua;" .. package.path
local stage = require("lib.stages")
local function run(split, opts)
  local t = stage.init{ N_a = 2, N_c = 60, L0 = 24, seed = 3, beta = 1e-2 }
  stage.compress(t, { to_phi = 0.5, progress = false })
  local o = { steps = split, progress = false }
  for k, v in pairs(opts) do o[k] = v end
  stage.quench(t, o)
  o.steps, o.label = 200 - split, "equilibrate"
  stage.quench(t, o)
  return t
end
local checks = 0
for name, opts in pairs{ active = { kT = 1e-4, f0 = 0.002, tau_p = 25 },
                         passive = { kT = 1e-4 },
                         damped = { kT = 1e-4, vertex_bath = "damped", vertex_gamma = 0.02 } } do
  local a, b = run(100, opts), run(200, opts)
  local pa, pb, va, vb = a.sys:positions(), b.sys:positions(), a.sys:velocities(), b.sys:velocities()
  for i = 1, #pa do
    for k = 1, 3 do
      assert(pa[i][k] == pb[i][k] and va[i][k] == vb[i][k],
             string.format("%s: site %d differs after quench + equilibrate: %.17g vs %.17g", name, i, pa[i][k], pb[i][k]))
    end
  end
  assert(a.dyn:wall_state().velocity == b.dyn:wall_state().velocity, name .. ": piston differs")
  checks = checks + 1
end
print(string.format("requench_continues: all %d checks passed", checks))
