-- Stage "init" (docs/model.md, protocol step 1): a dilute, de-mixed tissue in a cubic box of side L0,
-- walls in x, periodic in y and z. Cancer-cell centres are placed at random with
-- 2 < x < 12 and adipocyte centres with 16 < X < 68 (both scaled by L0 / 70), no overlaps.
-- Decision: the adipocyte range is clipped to X <= L0 - R_out (R_out = diameter / 2, the
-- outer radius with the vertex radii) so that no vertex starts outside the right wall: the
-- paper's 68 with diameter 6 would reach x = 71 > 70.
-- start = "mixed" (the inset of the paper's Fig. 4(b)): both populations over the whole box,
-- i.e. over the union 2 < x < 68 of the two de-mixed ranges (scaled, adipocytes clipped to
-- R_out <= X <= L0 - R_out); the adipocytes are placed first, the cells fill the gaps.
--
--   local tissue = require("lib.init"){ N_a = 28, N_c = 1500, L0 = 70, seed = 1 }
--
-- Returns a tissue table shared by every later stage:
--   tissue.sys (System), .cells and .vertices (Groups), .walls, .contacts, .shape (forces),
--   .tethers (nil until the tether stage), .dyn (nil until quench), .params (init options).
local iv = require("invasim")
local log = require("lib.log")

-- The contact and wall keys default to the engine's own (invasim.Contacts.defaults,
-- invasim.Walls.defaults): no copy of them here.
local contact = iv.Contacts.defaults
local spec = {
  N_a = 28, N_c = 1500, L0 = 70.0, seed = 1,
  diameters = { { 0.9, 1.1 }, type = "table" },  -- cancer-cell diameters, used in turn (bidisperse 50/50)
  diameter = 6.0,                  -- adipocyte outer diameter (vertex radii included)
  diameter_spread = 0.0,           -- adipocytes of many sizes: log-normal diameters of mean `diameter` (0: one size, the paper)
  vertex_diameter = 2.0,
  shape_param = 1.1,               -- reference shape parameter A_0
  start = { "demixed", choices = { "demixed", "mixed" } },  -- or "mixed": cells and adipocytes over the whole box
  eps_v = 1e3, eps_a = 1.0,        -- shape energy (docs/model.md: defaults and why)
  alpha = contact.alpha, beta = contact.beta,  -- cohesion of cancer cells (the compress stage may override)
  alpha_cv = contact.alpha_cv, beta_cv = contact.beta_cv,  -- adhesion of cells to adipocytes (0: the paper's repulsion)
  eps_cc = contact.eps_cc, eps_cv = contact.eps_cv, eps_vv = contact.eps_vv,
  wall_eps = iv.Walls.defaults.eps,
}

return function(opts)
  local o = iv.keywords("init", opts, spec)
  local L = o.L0
  local s = L / 70
  local sys = iv.System{ box = { L, L, L }, periodic = { false, true, true }, seed = o.seed }
  local mixed = o.start == "mixed"
  local R_out = o.diameter / 2
  local x_lo = mixed and math.max(2 * s, R_out) or 16 * s
  local x_hi = math.min(68 * s, L - R_out)
  if x_hi <= x_lo then
    error(string.format("init: L0 = %g is too small for adipocytes of diameter %g", L, o.diameter), 2)
  end
  local placed = sys:place{
    adipocytes = { n = o.N_a, x = { x_lo, x_hi }, diameter = o.diameter, spread = o.diameter_spread,
                   vertex_diameter = o.vertex_diameter, shape_param = o.shape_param },
    cells = { n = o.N_c, x = { 2 * s, (mixed and 68 or 12) * s }, diameters = o.diameters },
  }
  local tissue = {
    sys = sys,
    cells = sys:group("cancer"),
    vertices = sys:group("vertices"),
    walls = sys:add(iv.Walls{ eps = o.wall_eps }),
    contacts = sys:add(iv.Contacts{ alpha = o.alpha, beta = o.beta, alpha_cv = o.alpha_cv,
                                    beta_cv = o.beta_cv, eps_cc = o.eps_cc, eps_cv = o.eps_cv,
                                    eps_vv = o.eps_vv }),
    shape = sys:add(iv.Shape{ eps_v = o.eps_v, eps_a = o.eps_a }),
    params = o,
  }
  if o.diameter_spread > 0 then  -- beyond the paper (docs/model.md): said, as adhesion below
    local v = {}
    for _, a in ipairs(sys:adipocytes()) do v[#v + 1] = a.ref_volume end
    table.sort(v)
    log.say("init", "adipocytes of many sizes: log-normal diameters, mean %g, spread %g; reference volumes %.4g to %.4g (median %.4g)",
            o.diameter, o.diameter_spread, v[1], v[#v], v[(#v + 1) // 2])
  end
  if o.beta_cv > 0 then  -- beyond the paper (docs/model.md): said, so that no run hides it
    log.say("init", "cancer-adipocyte adhesion: beta_cv = %g, alpha_cv = %g (eps_cv = %g)",
            o.beta_cv, o.alpha_cv, o.eps_cv)
  end
  local phi = sys:packing()
  log.say("init", "%d cancer cells, %d adipocytes in a box %s, %s start, A_0 = %g; phi = %.4f (cells %.4f, adipocytes %.4f)",
          tissue.cells:size(), placed.adipocytes, log.box(sys:box().lengths), o.start, o.shape_param,
          phi.total, phi.cancer, phi.adipocyte)
  return tissue
end
