// Measurements of a System from Lua (src/measure), called by the production stage's
// observers every N steps (never inside the engine's step loop):
//   sys:voronoi{radical = false}   -> {A_t, A_t_max, A_ratio, cancer_adipocyte, cancer_wall,
//                                      adipocyte_wall, phi_a_local_mean, phi_a_local_std,
//                                      adipocyte_surface = {..}, adipocyte_wall_area = {..},
//                                      local_phi_a = {..}, seconds}
//   sys:shape_parameters()         -> {A_1, A_2, ...} 3D shape parameter per adipocyte
//   sys:slices{per_body = 10, offset_fraction = 0.5, seed = 1} -> {a, ...} 2D shape parameters
//   invasim.histogram(values, {lo =, hi =, bins = 20}) -> {edges, counts, density, below, above,
//                                                          invalid}
//   invasim.mean_error(values, {fraction = 1}) -> {mean, error, n, tau_int, window, resolved}
#include <lua.hpp>

#include <chrono>
#include <cmath>
#include <vector>

#include "core/memory_budget.hpp"
#include "core/names.hpp"
#include "lua/engine_types.hpp"
#include "lua/module.hpp"
#include "measure/mean_error.hpp"
#include "measure/slices.hpp"
#include "measure/voronoi.hpp"

namespace invasim::lua {

namespace {

// A Lua array of numbers at `index` (every entry a number).
std::vector<double> check_numbers(lua_State* L, int index, const char* what) {
  if (!lua_istable(L, index))
    fail_input(what, ": expected a list of numbers, got ", type_name_at(L, index));
  const lua_Integer n = lua_Integer(lua_rawlen(L, index));
  std::vector<double> values(static_cast<std::size_t>(n));
  for (lua_Integer i = 1; i <= n; ++i) {
    lua_rawgeti(L, index, i);
    if (lua_type(L, -1) != LUA_TNUMBER)
      fail_input(what, ": entry [", i, "] must be a number, got ", type_name_at(L, -1));
    values[std::size_t(i - 1)] = lua_tonumber(L, -1);
    lua_pop(L, 1);
  }
  return values;
}

int l_voronoi(lua_State* L) {
  const SystemHandle& sim = check<SystemHandle>(L, 1);
  VoronoiOptions options;
  options.interface_only = true;  // the per-site volumes and the faces are not returned
  if (!lua_isnoneornil(L, 2)) {
    Kwargs kw(L, 2, "voronoi");
    options.radical = kw.boolean("radical", options.radical);
    kw.finish();
  }
  const auto start = std::chrono::steady_clock::now();
  const VoronoiMeasurement m =
      engine_call("voronoi", [&] { return measure_voronoi(sim.system, options); });
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return push_record(L, {{"A_t", m.interface_area},
                         {"A_t_max", m.max_interface_area},
                         {"A_ratio", m.interface_ratio},
                         {"cancer_adipocyte", m.cancer_adipocyte_area},
                         {"cancer_wall", m.cancer_wall_area},
                         {"adipocyte_wall", m.adipocyte_wall_total},
                         {"phi_a_local_mean", m.mean_local_phi_a},
                         {"phi_a_local_std", m.std_local_phi_a},
                         {"seconds", seconds},
                         {"adipocyte_surface", m.adipocyte_surface},
                         {"adipocyte_wall_area", m.adipocyte_wall_area},
                         {"local_phi_a", m.local_phi_a}});
}

int l_slices(lua_State* L) {
  const SystemHandle& sim = check<SystemHandle>(L, 1);
  SliceOptions options;
  options.seed = sim.system.seed();
  if (!lua_isnoneornil(L, 2)) {
    Kwargs kw(L, 2, "slices");
    options.per_body = kw.integer<int>("per_body", options.per_body, Range::between(1, 8192));
    options.offset_fraction =
        kw.number("offset_fraction", options.offset_fraction, Range::between(0, 1));
    options.seed = kw.integer<std::uint64_t>("seed", options.seed, Range::at_least(0));
    kw.finish();
  }
  const auto slices = engine_call("slices", [&] { return random_slices(sim.system, options); });
  std::vector<double> shapes;
  shapes.reserve(slices.size());
  for (const BodySlice& s : slices) shapes.push_back(s.shape);
  push_value(L, shapes);
  return 1;
}

int l_histogram(lua_State* L) {
  const std::vector<double> values = check_numbers(L, 1, "histogram");
  Kwargs kw(L, 2, "histogram");
  const double lo = kw.number("lo");
  const double hi = kw.number("hi");
  const int bins = kw.integer<int>("bins", 20, Range::at_least(1));
  kw.finish();
  if (!(hi > lo) || !std::isfinite(hi - lo))
    fail_input("histogram: hi = ", hi, " must be greater than lo = ", lo,
               ", by a finite width (the bins' edges are lo + k (hi - lo) / bins)");
  // Per bin: edges, counts, density and the counts' copy (4 x 8 bytes) and three Lua table
  // slots (3 x 16 bytes).
  check_memory("histogram", "bins", double(bins), 80.0);
  const Histogram h = histogram(values, lo, hi, bins);
  return push_record(L, {{"edges", h.edges},
                         {"counts", std::vector<double>(h.counts.begin(), h.counts.end())},
                         {"density", h.density},
                         {"below", h.below},
                         {"above", h.above},
                         {"invalid", h.invalid}});
}

int l_mean_error(lua_State* L) {
  const std::vector<double> values = check_numbers(L, 1, "mean_error");
  double fraction = 1.0;
  if (!lua_isnoneornil(L, 2)) {
    Kwargs kw(L, 2, "mean_error");
    fraction = kw.number("fraction", fraction, Range{0.0, 1.0, true, false});  // (0, 1]
    kw.finish();
  }
  for (std::size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i]))
      fail_input("mean_error: values[", i + 1,
                 "] = ", std::isnan(values[i]) ? "nan" : cat(values[i]),
                 " is not a finite number (a mean and its error need finite samples)");
  const MeanError m = engine_call("mean_error", [&] { return mean_error_tail(values, fraction); });
  return push_record(L, {{"mean", m.mean},
                         {"error", m.error},
                         {"n", m.n},
                         {"tau_int", m.tau_int},
                         {"window", m.window},
                         {"resolved", m.resolved}});
}

}  // namespace

// System methods added to the System's method table (bind_system.cpp registers them).
const luaL_Reg kSystemMeasureMethods[] = {
    INVASIM_LUA_FN(voronoi),
    method<"shape_parameters",
           [](const SystemHandle& sim) { return body_shape_parameters(sim.system); }>(),
    INVASIM_LUA_FN(slices),
    {nullptr, nullptr},
};

void open_measure(lua_State* L) {
  add_functions(L, {INVASIM_LUA_FN(histogram), INVASIM_LUA_FN(mean_error)});
}

}  // namespace invasim::lua
