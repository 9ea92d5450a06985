// Helpers shared by the engine bindings (engine_types.hpp).
#include <lua.hpp>

#include "core/names.hpp"
#include "core/progress.hpp"
#include "lua/adapters.hpp"
#include "lua/engine_types.hpp"

namespace invasim::lua {

std::shared_ptr<Group> kw_group(Kwargs& kw, std::string_view key, bool required) {
  auto group =
      kw_object<Group>(kw, key, required, "a Group from sys:group(name) or sys:place{...}");
  if (group) require_current(*group, kw.owner() + ": key '" + std::string(key) + "'");
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

void push_force(lua_State* L, const ForceHandle& handle) {
  std::visit([L](const auto& h) { push(L, h); }, handle);
}

Record fire_state_record(const FireState& st) {
  return {{"dt", st.dt},
          {"alpha", st.alpha},
          {"n_positive", st.n_positive},
          {"steps", st.steps},
          {"wall_velocity", st.wall_velocity}};
}

void push_fire_result(lua_State* L, const FireResult& r) {
  Record record{{"converged", r.converged},
                {"steps", r.steps},
                {"max_force", r.max_force},
                {"energy", r.energy}};
  if (r.stopped) {
    record.push_back({"stopped", true});
    record.push_back({"fire_state", fire_state_record(r.state)});
  }
  push_record(L, record);
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
