// invasim.Fire{ftol = 1e-8, dt = 0.05, dt_max = 0.5, max_steps = 1e6}: the FIRE minimiser.
// fire:minimize(sys [, dyn] [, {contacts = {beta = 0, ...}, stop_on_signal = false,
//                                continue_from = {fire_state = ...}}])
//   -> {converged, steps, max_force, energy [, stopped = true, fire_state = {...}]}
// With a Dynamics that has a pressure wall, the left wall is minimised too (mechanical
// equilibrium at its P); `contacts` changes the System's Contacts parameters for this
// minimisation only (TemporaryContacts). With stop_on_signal, a SIGINT/SIGTERM ends it before
// the next iteration (stopped, the minimiser's state in fire_state, velocities kept);
// continue_from = {fire_state = that state} continues it, bit for bit.
#include <lua.hpp>

#include "core/names.hpp"
#include "core/stop_request.hpp"
#include "lua/adapters.hpp"
#include "lua/engine_fields.hpp"
#include "lua/module.hpp"
#include "setup/test_hooks.hpp"

namespace invasim::lua {

namespace {

// The keys of invasim.Fire{}.
const FieldTable<FireParams>& fire_table() {
  static const FieldTable<FireParams> table(
      "Fire", fire_fields<FireParams>([](FireParams& p) -> FireParams& { return p; }));
  return table;
}

}  // namespace

std::string LuaType<Fire>::describe(const Fire& f) {
  return fire_table().describe(f.params());
}

namespace {

int l_minimize(lua_State* L) {
  const Fire& fire = check<Fire>(L, 1);
  const std::shared_ptr<SystemHandle> sim = check_shared<SystemHandle>(L, 2);
  PressureWall* wall = nullptr;
  int options = 3;  // index of the options table: after the Dynamics, if any
  if (lua_type(L, 3) == LUA_TUSERDATA) {
    options = 4;
    DynamicsHandle& d = check<DynamicsHandle>(L, 3);
    if (!d.dynamics.pressure_wall())
      fail_input(
          "minimize: the Dynamics has no pressure wall (set one with "
          "dyn:pressure_wall{P = ...})");
    wall = prepare_dynamics(d, sim, "minimize");
  } else if (lua_isnil(L, 3)) {
    options = 4;
  } else if (!lua_isnone(L, 3) && !lua_istable(L, 3)) {
    check<DynamicsHandle>(L, 3);  // the error names the expected Dynamics
  }
  std::optional<Kwargs> kw;
  std::optional<TemporaryContacts> contacts;  // undone on every exit path
  FireControl control;
  if (!lua_isnoneornil(L, options)) {
    kw.emplace(L, options, "minimize");
    if (kw->boolean("stop_on_signal", false)) {
      control.stop = [] { return stop_requested() != 0; };
      pause_in_stoppable_minimize();  // test hook, off by default
    }
    if (kw->push("continue_from") != LUA_TNIL) {
      if (!lua_istable(L, -1))
        fail_input("minimize: key 'continue_from' must be a table {fire_state = ...}, got ",
                   type_name_at(L, -1));
      Kwargs from(L, lua_gettop(L), "minimize: continue_from");
      control.resume = read_fire_state(from);
      if (!control.resume) fail_input("minimize: continue_from needs its key 'fire_state'");
      from.finish();
    } else {
      lua_pop(L, 1);
    }
    temporary_contacts(*kw, *sim, contacts);
    kw->finish();
  }
  sim->changed();
  const FireResult r = engine_call("minimize", [&] {
    return fire.minimize(sim->system, sim->forces, wall,
                         control.stop || control.resume ? &control : nullptr);
  });
  push_fire_result(L, r);
  return 1;
}

}  // namespace

void open_fire(lua_State* L) {
  // fire:params() -> {ftol =, dt =, dt_max =, max_steps =}
  define_params_type<Fire, &fire_table, [](const Fire& f) { return f.params(); },
                     [](const FireParams& p) { return std::make_shared<Fire>(p); }>(
      L, {INVASIM_LUA_FN(minimize)});
}

}  // namespace invasim::lua
