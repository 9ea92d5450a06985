// Integration methods, each moving one Group inside a Dynamics:
//   invasim.Damped{group =, gamma = 0.2}
//   invasim.Langevin{group =, gamma = 0.2, kT =}
//   invasim.Active{group =, gamma = 0.2, f0 =, tau_p =, kT = 0, randomize = true}
// All three are the engine's Method; the Lua type is "Method".
#include <lua.hpp>

#include "lua/engine_types.hpp"
#include "lua/module.hpp"
#include "lua/names.hpp"

namespace invasim::lua {

std::string LuaType<MethodHandle>::describe(const MethodHandle& m) {
  const MethodParams& p = m.method->params();
  std::string text = cat(m.kind, "(group '", m.group->name, "' of ", m.group->sites.size(),
                         " sites, gamma=", p.gamma);
  if (m.kind != "Damped") text += cat(", kT=", p.kT);
  if (m.kind == "Active") text += cat(", f0=", p.f0, ", tau_p=", p.tau_p);
  return text + ")";
}

namespace {

void push_method(lua_State* L, const char* kind, std::shared_ptr<Group> group,
                 std::shared_ptr<Method> method) {
  push(L, std::make_shared<MethodHandle>(MethodHandle{kind, std::move(method), std::move(group)}));
}

int l_damped(lua_State* L) {
  Kwargs kw(L, 1, "Damped");
  auto group = kw_group(kw, "group");
  const double gamma = kw.number("gamma", 0.2, Range::non_negative());
  kw.finish();
  auto method = engine_call("Damped", [&] { return Method::damped(group->sites, gamma); });
  push_method(L, "Damped", std::move(group), std::move(method));
  return 1;
}

int l_langevin(lua_State* L) {
  Kwargs kw(L, 1, "Langevin");
  auto group = kw_group(kw, "group");
  const double gamma = kw.number("gamma", 0.2, Range::non_negative());
  const double kT = kw.number("kT", Range::non_negative());
  kw.finish();
  auto method = engine_call("Langevin", [&] { return Method::langevin(group->sites, gamma, kT); });
  push_method(L, "Langevin", std::move(group), std::move(method));
  return 1;
}

int l_active(lua_State* L) {
  Kwargs kw(L, 1, "Active");
  auto group = kw_group(kw, "group");
  const double gamma = kw.number("gamma", 0.2, Range::non_negative());
  const double f0 = kw.number("f0", Range::non_negative());
  const double tau_p = kw.number("tau_p", Range::non_negative());
  const double kT = kw.number("kT", 0.0, Range::non_negative());
  const bool randomize = kw.boolean("randomize", true);
  kw.finish();
  auto method =
      engine_call("Active", [&] { return Method::active(group->sites, gamma, f0, tau_p, kT); });
  if (randomize) {
    Simulation& sim = owner_of(group->owner, "Active: group '" + group->name + "'",
                               "make groups with sys:group(name)");
    method->randomize_orientations(sim.system, sim.system.step);
    sim.changed();
  }
  push_method(L, "Active", std::move(group), std::move(method));
  return 1;
}

int l_kind(lua_State* L) {
  const std::string& kind = check<MethodHandle>(L, 1).kind;
  lua_pushlstring(L, kind.data(), kind.size());
  return 1;
}

int l_group(lua_State* L) {
  push(L, check<MethodHandle>(L, 1).group);
  return 1;
}

// m:params() -> {gamma =, kT =, f0 =, tau_p =}
int l_params(lua_State* L) {
  const MethodParams& p = check<MethodHandle>(L, 1).method->params();
  lua_createtable(L, 0, 4);
  set_number(L, "gamma", p.gamma);
  set_number(L, "kT", p.kT);
  set_number(L, "f0", p.f0);
  set_number(L, "tau_p", p.tau_p);
  return 1;
}

const luaL_Reg kMethods[] = {
    {"kind", &lua_wrap<&l_kind>},
    {"group", &lua_wrap<&l_group>},
    {"params", &lua_wrap<&l_params>},
    {nullptr, nullptr},
};

}  // namespace

void open_method(lua_State* L) {
  define_type<MethodHandle>(L, kMethods);
  lua_pushcfunction(L, &lua_wrap<&l_damped>);
  lua_setfield(L, -2, "Damped");
  lua_pushcfunction(L, &lua_wrap<&l_langevin>);
  lua_setfield(L, -2, "Langevin");
  lua_pushcfunction(L, &lua_wrap<&l_active>);
  lua_setfield(L, -2, "Active");
}

}  // namespace invasim::lua
