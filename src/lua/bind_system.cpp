// invasim.System{box = {Lx, Ly, Lz}, periodic = {false, true, true}, seed = 1}: the state, its
// forces and the queries on it (docs/lua.md, "System").
#include <lua.hpp>

#include <cmath>
#include <numeric>

#include "core/names.hpp"
#include "lua/adapters.hpp"
#include "lua/engine_types.hpp"
#include "lua/fields.hpp"
#include "lua/module.hpp"
#include "measure/kinetic.hpp"
#include "measure/packing.hpp"
#include "mesh/geometry.hpp"
#include "run/energies.hpp"
#include "setup/masses.hpp"
#include "setup/placement.hpp"
#include "setup/velocities.hpp"

namespace invasim::lua {

std::string LuaType<SystemHandle>::describe(const SystemHandle& sim) {
  const Vec3 L = sim.system.box().lengths();
  return cat("System(", sim.system.n_sites(), " sites, ", sim.system.bodies().size(),
             " adipocytes, box ", L[0], " x ", L[1], " x ", L[2], ", step ", sim.system.step, ")");
}

namespace {

// The keys of invasim.System{} (the engine's System takes box and seed without defaults: these
// are their one defaults).
struct SystemKeys {
  std::vector<double> box;
  std::vector<bool> periodic{false, true, true};  // walls in x, periodic in y and z
  std::uint64_t seed = 1;
};

const FieldTable<SystemKeys>& system_fields() {
  using P = SystemKeys;
  static const FieldTable<P> table("System", [] {
    Field<P> box;
    box.info = field_declaration("box", {"table"}, shown_range(Range::positive(), false), "sigma",
                                 "box side lengths (the box spans [0, L] in each axis)");
    box.info.list_form = "list of 3 numbers";
    box.info.required = true;
    box.read = [](Kwargs& kw, P& p, bool) { p.box = kw.number_list("box", 3, Range::positive()); };
    Field<P> periodic;
    periodic.info = field_declaration("periodic", {"table"}, std::nullopt, "",
                                      "periodic axes (default: walls in x, periodic in y and z)");
    periodic.info.list_form = "list of 3 booleans";
    periodic.read = [](Kwargs& kw, P& p, bool) {
      if (auto v = kw.maybe_boolean_list("periodic", 3)) p.periodic = *v;
    };
    return std::vector<Field<P>>{box, periodic,
                                 integer<P>("seed", &P::seed, Range::non_negative(), "",
                                            "random seed (placement, noise, orientations)")};
  }());
  return table;
}

int l_new(lua_State* L) {
  Kwargs kw(L, 1, "System");
  const SystemKeys k = system_fields().make(kw);
  const std::vector<double>& lengths = k.box;
  const std::vector<bool>& periodic = k.periodic;
  const std::uint64_t seed = k.seed;
  auto sim = engine_call("System", [&] {
    const Box box(Vec3::Zero(), Vec3(lengths[0], lengths[1], lengths[2]),
                  {periodic[0], periodic[1], periodic[2]});
    return std::make_shared<SystemHandle>(box, static_cast<std::uint64_t>(seed));
  });
  push(L, std::move(sim));
  return 1;
}

// The x range {lo, hi} of a placement table.
invasim::Range read_x(Kwargs& kw) {
  const auto x = kw.number_list("x", 2);
  return {x[0], x[1]};
}

// A refused number as messages show it: "nan" whatever the sign bit (printf gives "-nan").
std::string number_text(double v) {
  return std::isnan(v) ? "nan" : cat(v);
}

// Pushes list key `key` of kw and returns its length; anything but a non-empty table is
// refused ("must be a non-empty list of <form>").
std::size_t push_nonempty_list(Kwargs& kw, const char* key, const char* form) {
  lua_State* L = kw.state();
  const int type = kw.push(key);
  const std::size_t n = type == LUA_TTABLE ? lua_rawlen(L, -1) : 0;
  if (n == 0)
    fail_input(kw.owner(), ": key '", key, "' must be a non-empty list of ", form, ", got ",
               type == LUA_TTABLE ? "an empty table" : type_name_at(L, -1));
  return n;
}

// Diameters (of cancer cells, or of adipocytes of many sizes): a non-empty list of positive
// numbers, any length.
std::vector<double> read_diameters(Kwargs& kw, std::vector<double> fallback) {
  if (!kw.has("diameters")) return fallback;
  lua_State* L = kw.state();
  const std::size_t n = push_nonempty_list(kw, "diameters", "numbers");
  std::vector<double> d(n);
  for (std::size_t i = 0; i < n; ++i) {
    lua_rawgeti(L, -1, static_cast<lua_Integer>(i + 1));
    if (lua_type(L, -1) != LUA_TNUMBER || !(lua_tonumber(L, -1) > 0) ||
        !std::isfinite(lua_tonumber(L, -1)))
      fail_input(
          kw.owner(), ": key 'diameters[", i + 1, "]' must be a number > 0, got ",
          lua_type(L, -1) == LUA_TNUMBER ? number_text(lua_tonumber(L, -1)) : type_name_at(L, -1));
    d[i] = lua_tonumber(L, -1);
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  return d;
}

// Given cell centres: a non-empty list of {x, y, z} lists of finite numbers.
std::vector<Vec3> read_positions(Kwargs& kw) {
  lua_State* L = kw.state();
  const std::size_t n = push_nonempty_list(kw, "positions", "{x, y, z}");
  std::vector<Vec3> r(n);
  for (std::size_t i = 0; i < n; ++i) {
    lua_rawgeti(L, -1, static_cast<lua_Integer>(i + 1));
    const bool list = lua_type(L, -1) == LUA_TTABLE && lua_rawlen(L, -1) == 3;
    for (int a = 0; list && a < 3; ++a) {
      lua_rawgeti(L, -1, a + 1);
      const bool finite = lua_type(L, -1) == LUA_TNUMBER && std::isfinite(lua_tonumber(L, -1));
      if (!finite)
        fail_input(kw.owner(), ": key 'positions[", i + 1, "][", a + 1,
                   "]' must be a finite number, got ",
                   lua_type(L, -1) == LUA_TNUMBER ? number_text(lua_tonumber(L, -1))
                                                  : type_name_at(L, -1));
      r[i][a] = lua_tonumber(L, -1);
      lua_pop(L, 1);
    }
    if (!list)
      fail_input(kw.owner(), ": key 'positions[", i + 1, "]' must be a list of 3 numbers, got ",
                 lua_type(L, -1) == LUA_TTABLE ? cat("a table of length ", lua_rawlen(L, -1))
                                               : type_name_at(L, -1));
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  return r;
}

// Every site index of the System, 0 .. n - 1.
std::vector<int> all_sites(const SystemHandle& sim) {
  std::vector<int> all(sim.system.n_sites());
  std::iota(all.begin(), all.end(), 0);
  return all;
}

void push_group(lua_State* L, const std::shared_ptr<SystemHandle>& sim, std::string name,
                std::vector<int> sites) {
  const std::uint64_t epoch = sim->system.site_epoch();
  push(L, std::make_shared<Group>(Group{std::move(name), std::move(sites), sim, epoch}));
}

// sys:place{cells = {n =, diameters =, x = {lo, hi}} or {positions = {{x, y, z}, ...},
// diameters =}, adipocytes = {n =, diameter =,
// diameters =, spread =, vertex_diameter =, shape_param =, subdivisions =, random_rotation =,
// x = {lo, hi}}}
int l_place(lua_State* L) {
  auto& sim = check_shared<SystemHandle>(L, 1);
  Kwargs kw(L, 2, "place");
  SpherePlacement cells;
  MeshPlacement meshes;
  if (auto c = kw.maybe_table("cells")) {
    cells.diameters = read_diameters(*c, cells.diameters);
    if (c->has("positions")) {  // where they are given: n follows, no x range
      cells.positions = read_positions(*c);
      cells.n = c->integer<int>("n", int(cells.positions.size()), Range::non_negative());
      for (const char* random_only : {"x", "max_attempts"})
        if (c->has(random_only))
          fail_input("place: cells.", random_only,
                     " goes with random placement; with positions the cells are placed as given");
    } else {
      cells.n = c->integer<int>("n", Range::non_negative());
      cells.x = read_x(*c);
      cells.max_attempts_per_cell =
          c->number("max_attempts", cells.max_attempts_per_cell, Range::at_least(1));
    }
    c->finish();
  }
  if (auto a = kw.maybe_table("adipocytes")) {
    meshes.n = a->integer<int>("n", Range::non_negative());
    meshes.diameter = a->number("diameter", meshes.diameter, Range::positive());
    meshes.diameters = read_diameters(*a, {});
    meshes.spread = a->number("spread", meshes.spread, Range::non_negative());
    meshes.vertex_diameter =
        a->number("vertex_diameter", meshes.vertex_diameter, Range::positive());
    meshes.shape_param = a->number("shape_param", meshes.shape_param, Range::at_least(1));
    meshes.subdivisions =
        a->integer<int>("subdivisions", meshes.subdivisions, Range::between(0, 4));
    meshes.random_rotation = a->boolean("random_rotation", meshes.random_rotation);
    meshes.volume_grid = a->number("volume_grid", meshes.volume_grid, Range::positive());
    meshes.x = read_x(*a);
    meshes.max_attempts_per_body =
        a->number("max_attempts", meshes.max_attempts_per_body, Range::at_least(1));
    a->finish();
  }
  kw.finish();
  const std::size_t first_body = sim->system.bodies().size();
  sim->changed();
  const PlacementResult placed =
      engine_call("place", [&] { return place_random(sim->system, meshes, cells); });
  std::vector<int> vertices;
  for (std::size_t b = first_body; b < sim->system.bodies().size(); ++b) {
    const MeshBody& body = sim->system.bodies()[b];
    for (int v = 0; v < body.n_vertices(); ++v) vertices.push_back(body.first_site + v);
  }
  push_group(L, sim, "placed cells", placed.cells);
  push_group(L, sim, "placed vertices", std::move(vertices));
  const auto n_bodies = static_cast<long long>(placed.bodies.size());
  protected_call(L, 2, 1, [n_bodies](lua_State* S) noexcept {
    lua_createtable(S, 0, 3);
    lua_pushvalue(S, 1);
    lua_setfield(S, -2, "cells");
    lua_pushvalue(S, 2);
    lua_setfield(S, -2, "vertices");
    lua_pushinteger(S, n_bodies);
    lua_setfield(S, -2, "adipocytes");
    return 1;
  });
  return 1;
}

// sys:group(name): "cancer", "vertices" or "all", as of now.
int l_group(lua_State* L) {
  auto& sim = check_shared<SystemHandle>(L, 1);
  const std::string name = arg_string(L, 2);
  no_arguments_after(L, 2);
  const std::vector<std::string> names{"all", "cancer", "vertices"};
  std::vector<int> sites;
  if (name == "cancer")
    sites = sim->system.sites_of_kind(SiteKind::kCancer);
  else if (name == "vertices")
    sites = sim->system.sites_of_kind(SiteKind::kVertex);
  else if (name == "all")
    sites = all_sites(*sim);
  else
    fail_input("group: unknown group '", name, "'", did_you_mean(name, names),
               "; groups: ", join_names(names));
  push_group(L, sim, name, std::move(sites));
  return 1;
}

// sys:box() -> {lengths = {..}, lo = {..}, hi = {..}, periodic = {..}, volume = V}
int l_box(lua_State* L) {
  const Box& box = check<SystemHandle>(L, 1).system.box();
  no_arguments_after(L, 1);
  return push_record(
      L, {{"lengths", box.lengths()},
          {"lo", box.lo()},
          {"hi", box.hi()},
          {"periodic", std::vector<bool>{box.periodic(0), box.periodic(1), box.periodic(2)}},
          {"volume", box.volume()}});
}

int l_packing(lua_State* L) {
  const PackingFractions phi = packing_fractions(check<SystemHandle>(L, 1).system);
  no_arguments_after(L, 1);
  return push_record(L,
                     {{"total", phi.total}, {"cancer", phi.cancer}, {"adipocyte", phi.adipocyte}});
}

// The sites of the optional Group argument at `index` (all sites when absent).
std::vector<int> group_arg(lua_State* L, int index, const SystemHandle& sim, const char* what) {
  const Group* group = lua_isnoneornil(L, index) ? nullptr : &check<Group>(L, index);
  no_arguments_after(L, index);
  if (!group) return all_sites(sim);
  require_same_system(*group, sim, what);
  require_current(*group, what);
  return group->sites;
}

// sys:temperature([group]): kT = 1/(3N) sum m v^2 over the group (all sites by default).
int l_temperature(lua_State* L) {
  const SystemHandle& sim = check<SystemHandle>(L, 1);
  lua_pushnumber(L, temperature(sim.system, group_arg(L, 2, sim, "temperature")));
  return 1;
}

// sys:positions / velocities / orientations([group]) -> {{x, y, z}, ...}: one per-site vector
// of the group's sites, in the group's order.
int push_site_vectors(lua_State* L, std::vector<Vec3> Sites::*field, const char* what) {
  const SystemHandle& sim = check<SystemHandle>(L, 1);
  const std::vector<int> sites = group_arg(L, 2, sim, what);
  const std::vector<Vec3>& v = sim.system.sites().*field;
  return push_results(L, 1, [&sites, &v](lua_State* S) noexcept {
    push_list(S, sites.size(), [&](std::size_t k) { push_vec3(S, v[sites[k]]); });
    return 1;
  });
}
// Positions are wrapped into the box on the periodic axes.
int l_positions(lua_State* L) {
  return push_site_vectors(L, &Sites::pos, "positions");
}
int l_velocities(lua_State* L) {
  return push_site_vectors(L, &Sites::vel, "velocities");
}
// The self-propulsion directions n_i: unit vectors for the sites an Active method moves, (0, 0, 0)
// for sites never made active.
int l_orientations(lua_State* L) {
  return push_site_vectors(L, &Sites::orient, "orientations");
}

// sys:adipocytes() -> {{volume =, ref_volume =, ref_volume_initial =, area =,
// shape_parameter =, ref_shape_parameter =, centre = {..}}, ...}
// per adipocyte: mesh volume v_i, its reference now and when the body was made (they differ
// after lipolysis), mesh area, 3D shape parameter, the reference one A_0 (from the sum of the
// reference face areas and v_i0), and the vertex centroid (unwrapped).
int l_adipocytes(lua_State* L) {
  const SystemHandle& sim = check<SystemHandle>(L, 1);
  no_arguments_after(L, 1);
  const auto& bodies = sim.system.bodies();
  std::vector<Record> rows;
  std::vector<Vec3> x;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const MeshBody& body = bodies[b];
    x.resize(body.n_vertices());
    sim.system.body_vertices(int(b), x.data());
    const double volume = mesh_volume(*body.topology, x.data());
    const double area = mesh_area(*body.topology, x.data());
    double ref_area = 0.0;
    for (double a : body.ref_area) ref_area += a;
    rows.push_back({{"volume", volume},
                    {"ref_volume", body.ref_volume},
                    {"ref_volume_initial", body.ref_volume_initial},
                    {"area", area},
                    {"shape_parameter", shape_parameter(area, volume)},
                    {"ref_shape_parameter", shape_parameter(ref_area, body.ref_volume)},
                    {"centre", vertex_centroid(body.n_vertices(), x.data())}});
  }
  return push_records(L, rows);
}

// sys:set_velocities{group = g, kT = x}: Maxwell-Boltzmann velocities (stream kVelocity,
// keyed by the current step), so that <m v^2> = 3 kT.
int l_set_velocities(lua_State* L) {
  SystemHandle& sim = check<SystemHandle>(L, 1);
  Kwargs kw(L, 2, "set_velocities");
  const auto group = kw_group(kw, "group", false);
  const double kT = kw.number("kT", Range::non_negative());
  kw.finish();
  if (group) require_same_system(*group, sim, "set_velocities");
  const std::vector<int> sites = group ? group->sites : all_sites(sim);
  engine_call("set_velocities", [&] { set_maxwell_boltzmann(sim.system, sites, kT); });
  sim.changed();
  return 0;
}

// sys:set_mass{group = g, mass = m}: the sites of g get mass m (velocities kept); the
// protocols give the adipocyte vertices their vertex_mass this way before the dynamics starts.
int l_set_mass(lua_State* L) {
  SystemHandle& sim = check<SystemHandle>(L, 1);
  Kwargs kw(L, 2, "set_mass");
  const auto group = kw_group(kw, "group", true);
  const double mass = kw.number("mass", Range::positive());
  kw.finish();
  require_same_system(*group, sim, "set_mass");
  engine_call("set_mass", [&] { set_masses(sim.system, group->sites, mass); });
  sim.changed();
  return 0;
}

// sys:add(force): appends a force term (Contacts, Walls, Shape, Tethers); returns it.
int l_add(lua_State* L) {
  auto& sim = check_shared<SystemHandle>(L, 1);
  if (is<Contacts>(L, 2))
    attach_force(sim, check_shared<Contacts>(L, 2), "Contacts");
  else if (is<Walls>(L, 2))
    attach_force(sim, check_shared<Walls>(L, 2), "Walls");
  else if (is<Shape>(L, 2))
    attach_force(sim, check_shared<Shape>(L, 2), "Shape");
  else if (is<Tethers>(L, 2))
    attach_force(sim, check_shared<Tethers>(L, 2), "Tethers");
  else
    throw InputError(bad_argument(L, 2, "force (Contacts, Walls, Shape or Tethers)"));
  lua_settop(L, 2);
  return 1;
}

// sys:forces() -> {force, ...} in the order added.
int l_forces(lua_State* L) {
  const SystemHandle& sim = check<SystemHandle>(L, 1);
  no_arguments_after(L, 1);
  push_list(L, sim.handles.size(), [&](std::size_t k) { push_force(L, sim.handles[k]); });
  return 1;
}

// sys:compute() -> {total = U, contact = .., wall = .., shape = .., tether = .., virial = {..}}
// (a second term of the same kind is named contact2, ...). An observation: the site forces
// (which a Dynamics keeps between steps) are restored afterwards, so a callback may call it
// without disturbing the run.
int l_compute(lua_State* L) {
  SystemHandle& sim = check<SystemHandle>(L, 1);
  no_arguments_after(L, 1);
  EnergyTerms e;
  try {
    e = engine_call("compute", [&] { return observe_energies(sim.system, sim.forces); });
  } catch (...) {
    sim.changed();  // site forces left as they are: a Dynamics re-prepares
    throw;
  }
  Record record{{"total", e.total.energy}, {"virial", e.total.virial}};
  for (std::size_t k = 0; k < e.names.size(); ++k) record.push_back({e.names[k], e.energies[k]});
  return push_record(L, record);
}

const luaL_Reg kMethods[] = {
    INVASIM_LUA_FN(place),
    INVASIM_LUA_FN(group),
    getter<SystemHandle, [](const SystemHandle& s) { return s.system.n_sites(); }>("n_sites"),
    getter<SystemHandle, [](const SystemHandle& s) { return s.system.bodies().size(); }>(
        "n_adipocytes"),
    getter<SystemHandle, [](const SystemHandle& s) { return s.system.step; }>("step"),
    getter<SystemHandle, [](const SystemHandle& s) { return s.system.time; }>("time"),
    INVASIM_LUA_FN(box),
    INVASIM_LUA_FN(packing),
    INVASIM_LUA_FN(temperature),
    INVASIM_LUA_FN(set_velocities),
    INVASIM_LUA_FN(set_mass),
    INVASIM_LUA_FN(positions),
    INVASIM_LUA_FN(velocities),
    INVASIM_LUA_FN(orientations),
    INVASIM_LUA_FN(adipocytes),
    INVASIM_LUA_FN(add),
    INVASIM_LUA_FN(forces),
    INVASIM_LUA_FN(compute),
    {nullptr, nullptr},
};

}  // namespace

void open_system(lua_State* L) {
  // The System's own methods plus the measurements (bind_measure.cpp).
  RegList methods({});
  for (const luaL_Reg* r = kMethods; r->name; ++r) methods.add(*r);
  for (const luaL_Reg* r = kSystemMeasureMethods; r->name; ++r) methods.add(*r);
  define_type<SystemHandle>(L, methods.data());
  set_constructor(L, "System", &lua_wrap<&l_new>, system_fields().infos());
}

}  // namespace invasim::lua
