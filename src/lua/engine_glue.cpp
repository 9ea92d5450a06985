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

void temporary_contacts(Kwargs& kw, SystemHandle& sim, std::optional<TemporaryContacts>& out) {
  std::optional<Kwargs> keys = kw.maybe_table("contacts");
  if (!keys) return;
  std::shared_ptr<ContactForce> force = only_contacts(sim, kw.owner() + ": key 'contacts'");
  ContactParams changed = force->params();
  read_contact_params(*keys, changed);
  keys->finish();
  engine_call(kw.owner(), [&] { out.emplace(sim, std::move(force), changed); });
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
