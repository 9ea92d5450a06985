// The setup stages that reshape the box (setup/compression.hpp):
//   invasim.compress(sys, {to_phi =, step = 0.03, ftol =, dt =, dt_max =, max_steps =,
//                          max_compressions = 1e5, progress = p, callback = f,
//                          continue_from = {steps =, fire_steps =, converged =, max_force =},
//                          contacts = {beta = 0, ...}})
//   -> report {steps, fire_steps, converged, phi, max_force, box, stopped}
//   (f(report) is called after every compression step with the report so far; after it, a
//   stop signal (SIGINT/SIGTERM, invasim.interrupted()) stops the compression at that step
//   boundary with stopped = true; continue_from resumes the counters of such a report;
//   contacts changes the System's Contacts parameters for this call only: TemporaryContacts)
//   invasim.rescale(sys, {phi_a =, ftol =, dt =, dt_max =, max_steps =}) -> FIRE result
// ftol, dt, dt_max and max_steps set the FIRE minimisation after each box change.
#include <lua.hpp>

#include "core/stop_request.hpp"
#include "lua/engine_types.hpp"
#include "lua/module.hpp"
#include "lua/progress.hpp"
#include "lua/temporary_contacts.hpp"
#include "setup/compression.hpp"

namespace invasim::lua {

namespace {

// The compression report as a Lua table {steps, fire_steps, converged, phi, max_force, box}.
void push_compression_report(lua_State* L, const CompressionReport& r) {
  protected_call(L, 0, 1, [&r](lua_State* S) noexcept {
    lua_createtable(S, 0, 7);
    set_boolean(S, "stopped", r.stopped);
    set_integer(S, "steps", static_cast<long long>(r.steps));
    set_integer(S, "fire_steps", static_cast<long long>(r.fire_steps));
    set_boolean(S, "converged", r.converged);
    set_number(S, "phi", r.phi);
    set_number(S, "max_force", r.max_force);
    push_vec3(S, r.box_lengths);
    lua_setfield(S, -2, "box");
    return 1;
  });
}

int l_compress(lua_State* L) {
  const std::shared_ptr<Simulation> sim = check_shared<Simulation>(L, 1);
  Kwargs kw(L, 2, "compress");
  CompressionParams p;
  p.target_phi = kw.number("to_phi", Range::between(0, 1));
  p.step = kw.number("step", p.step, Range::between(0, 1));
  p.fire = kw_fire(kw);
  p.max_steps = kw.integer<std::size_t>("max_compressions", p.max_steps, Range::at_least(1));
  Progress* progress = nullptr;
  if (kw.push("progress") != LUA_TNIL) {
    progress = test_progress(L, -1);
    if (!progress)
      fail_input("compress: key 'progress' must be a Progress, got ", type_name_at(L, -1));
  }
  int callback = 0;  // stack index of the Lua callback, 0 if none
  if (kw.push("callback") != LUA_TNIL) {
    if (!lua_isfunction(L, -1))
      fail_input("compress: key 'callback' must be a function, got ", type_name_at(L, -1));
    callback = lua_gettop(L);
  } else {
    lua_pop(L, 1);
  }
  CompressionReport so_far;
  if (kw.push("continue_from") != LUA_TNIL) {
    if (!lua_istable(L, -1))
      fail_input("compress: key 'continue_from' must be a table, got ", type_name_at(L, -1));
    Kwargs from(L, lua_gettop(L), "compress: continue_from");
    so_far.steps = from.integer<std::size_t>("steps", Range::at_least(0));
    so_far.fire_steps = from.integer<std::uint64_t>("fire_steps", Range::at_least(0));
    so_far.converged = from.boolean("converged");
    so_far.max_force = from.number("max_force", Range::at_least(0));
    from.finish();
  } else {
    lua_pop(L, 1);
  }
  const TemporaryContacts contacts(kw, *sim, "compress");  // undone on every exit path
  kw.finish();
  CompressionCallback on_step = [&](const CompressionReport& r) {
    if (progress) progress->update(static_cast<long long>(r.steps));
    if (callback) {
      lua_pushvalue(L, callback);
      push_compression_report(L, r);
      call_lua(L, 1, 0);
    }
    return stop_requested() == 0;  // the caller checks invasim.interrupted()
  };
  sim->changed();
  const CompressionReport r = engine_call(
      "compress", [&] { return compress_to_phi(sim->system, sim->forces, p, on_step, so_far); });
  push_compression_report(L, r);
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
