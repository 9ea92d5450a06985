// The setup stages that reshape the box (setup/compression.hpp):
//   invasim.compress(sys, {to_phi =, step = 0.03, ftol =, dt =, dt_max =, max_steps =,
//                          max_compressions = 1e5, progress = p}) -> report
//   invasim.rescale(sys, {phi_a =, ftol =, dt =, dt_max =, max_steps =}) -> FIRE result
// ftol, dt, dt_max and max_steps set the FIRE minimisation after each box change.
#include <lua.hpp>

#include "lua/engine_types.hpp"
#include "lua/module.hpp"
#include "lua/progress.hpp"
#include "setup/compression.hpp"

namespace invasim::lua {

namespace {

int l_compress(lua_State* L) {
  const std::shared_ptr<Simulation> sim = check_shared<Simulation>(L, 1);
  Kwargs kw(L, 2, "compress");
  CompressionParams p;
  p.target_phi = kw.number("to_phi", Range::between(0, 1));
  p.step = kw.number("step", p.step, Range::between(0, 1));
  p.fire = kw_fire(kw);
  p.max_steps = static_cast<std::size_t>(
      kw.integer("max_compressions", static_cast<long long>(p.max_steps), Range::at_least(1)));
  Progress* progress = nullptr;
  if (kw.push("progress") != LUA_TNIL) {
    progress = test_progress(L, -1);
    if (!progress)
      fail_input("compress: key 'progress' must be a Progress, got ", type_name_at(L, -1));
  }
  kw.finish();
  CompressionCallback on_step;
  if (progress)
    on_step = [progress](const CompressionReport& r) {
      progress->update(static_cast<long long>(r.steps));
    };
  sim->changed();
  const CompressionReport r = engine_call(
      "compress", [&] { return compress_to_phi(sim->system, sim->forces, p, on_step); });
  lua_createtable(L, 0, 6);
  set_integer(L, "steps", static_cast<long long>(r.steps));
  set_integer(L, "fire_steps", static_cast<long long>(r.fire_steps));
  set_boolean(L, "converged", r.converged);
  set_number(L, "phi", r.phi);
  set_number(L, "max_force", r.max_force);
  push_vec3(L, r.box_lengths);
  lua_setfield(L, -2, "box");
  return 1;
}

int l_rescale(lua_State* L) {
  const std::shared_ptr<Simulation> sim = check_shared<Simulation>(L, 1);
  Kwargs kw(L, 2, "rescale");
  const double phi_a = kw.number("phi_a", Range::between(0, 1));
  const FireParams fire = kw_fire(kw);
  kw.finish();
  sim->changed();
  const FireResult r = engine_call(
      "rescale", [&] { return rescale_to_phi_a(sim->system, sim->forces, phi_a, fire); });
  push_fire_result(L, r);
  return 1;
}

}  // namespace

void open_compression(lua_State* L) {
  lua_pushcfunction(L, &lua_wrap<&l_compress>);
  lua_setfield(L, -2, "compress");
  lua_pushcfunction(L, &lua_wrap<&l_rescale>);
  lua_setfield(L, -2, "rescale");
}

}  // namespace invasim::lua
