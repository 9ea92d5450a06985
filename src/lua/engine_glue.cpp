// Helpers shared by the engine bindings (engine_types.hpp).
#include <lua.hpp>

#include "core/names.hpp"
#include "core/progress.hpp"
#include "lua/engine_types.hpp"

namespace invasim::lua {

std::shared_ptr<Group> kw_group(Kwargs& kw, std::string_view key, bool required) {
  lua_State* L = kw.state();
  const int type = kw.push(key);
  if (type == LUA_TNIL) {
    lua_pop(L, 1);
    if (required)
      fail_input(kw.owner(), ": missing required key '", key,
                 "' (a Group, from sys:group(name) or sys:place{...})");
    return nullptr;
  }
  auto* slot = test<Group>(L, -1);
  if (slot == nullptr)
    fail_input(kw.owner(), ": key '", key,
               "' must be a Group (from sys:group(name) or sys:place{...}), got ",
               type_name_at(L, -1));
  if (!*slot) fail_input(kw.owner(), ": key '", key, "': Group object is no longer valid");
  std::shared_ptr<Group> group = *slot;
  lua_pop(L, 1);
  require_current(*group, kw.owner() + ": key '" + std::string(key) + "'");
  return group;
}

SystemHandle& owner_of(const std::weak_ptr<SystemHandle>& owner, const std::string& what,
                       const std::string& hint) {
  if (auto sim = owner.lock()) return *sim;
  if (!owner.owner_before(std::weak_ptr<SystemHandle>{}) &&
      !std::weak_ptr<SystemHandle>{}.owner_before(owner))
    fail_input(what, ": not in a System; ", hint);
  fail_input(what, ": its System no longer exists");
}

void require_same_system(const Group& group, const SystemHandle& sim, const std::string& what) {
  if (group.owner.lock().get() != &sim)
    fail_input(what, ": group '", group.name, "' belongs to another System");
}

void require_current(const Group& group, const std::string& what) {
  const auto sim = group.owner.lock();
  if (sim && sim->system.site_epoch() != group.epoch)
    fail_input(what, ": group '", group.name,
               "' was made before cells divided or died, and its site indices name other cells "
               "now; make it again (sys:group{...})");
}

void push_vec3(lua_State* L, const Vec3& v) noexcept {
  push_list(L, 3, [&](std::size_t a) { lua_pushnumber(L, v[int(a)]); });
}

void set_number(lua_State* L, const char* key, double value) noexcept {
  lua_pushnumber(L, value);
  lua_setfield(L, -2, key);
}

void set_integer(lua_State* L, const char* key, long long value) noexcept {
  lua_pushinteger(L, value);
  lua_setfield(L, -2, key);
}

void set_boolean(lua_State* L, const char* key, bool value) noexcept {
  lua_pushboolean(L, value);
  lua_setfield(L, -2, key);
}

void push_number_list(lua_State* L, const double* values, std::size_t n) noexcept {
  push_list(L, n, [&](std::size_t i) { lua_pushnumber(L, values[i]); });
}

void push_integer_list(lua_State* L, const int* values, std::size_t n) noexcept {
  push_list(L, n, [&](std::size_t i) { lua_pushinteger(L, values[i]); });
}

void push_force(lua_State* L, const ForceHandle& handle) {
  std::visit([L](const auto& h) { push(L, h); }, handle);
}

// Sets field "fire_state" of the table on top of S to {dt, alpha, n_positive, steps,
// wall_velocity}.
void set_fire_state(lua_State* S, const FireState& st) noexcept {
  lua_createtable(S, 0, 5);
  set_number(S, "dt", st.dt);
  set_number(S, "alpha", st.alpha);
  set_integer(S, "n_positive", st.n_positive);
  set_integer(S, "steps", static_cast<long long>(st.steps));
  set_number(S, "wall_velocity", st.wall_velocity);
  lua_setfield(S, -2, "fire_state");
}

void push_fire_result(lua_State* L, const FireResult& r) {
  protected_call(L, 0, 1, [&r](lua_State* S) noexcept {
    lua_createtable(S, 0, 6);
    set_boolean(S, "converged", r.converged);
    set_integer(S, "steps", static_cast<long long>(r.steps));
    set_number(S, "max_force", r.max_force);
    set_number(S, "energy", r.energy);
    if (r.stopped) {
      set_boolean(S, "stopped", true);
      set_fire_state(S, r.state);
    }
    return 1;
  });
}

std::optional<FireState> read_fire_state(Kwargs& kw) {
  auto f = kw.maybe_table("fire_state");
  if (!f) return std::nullopt;
  FireState st;
  st.dt = f->number("dt", Range::greater_than(0));
  st.alpha = f->number("alpha", Range::between(0, 1));
  st.n_positive = f->integer<int>("n_positive", Range::at_least(0));
  st.steps = f->integer<std::uint64_t>("steps", Range::at_least(0));
  st.wall_velocity = f->number("wall_velocity", 0.0);
  f->finish();
  return st;
}

}  // namespace invasim::lua
