// Integration methods, each moving one Group inside a Dynamics:
//   invasim.Damped{group =, gamma = 0.2}
//   invasim.Langevin{group =, gamma = 0.2, kT =}
//   invasim.Active{group =, gamma = 0.2, f0 =, tau_p =, kT = 0, randomize = true}
// All three are the engine's Method; the Lua type is "Method". kT and f0 take a number or an
// invasim.ramp{}; tau_p may be math.huge (frozen orientations). m:set{...} changes gamma, kT,
// f0, tau_p between runs (a number clears a ramp of that key).
#include <lua.hpp>

#include <cmath>
#include <optional>

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

// tau_p: a number >= 0, or math.huge for frozen orientations (Kwargs numbers must be finite).
double kw_tau_p(Kwargs& kw, std::optional<double> fallback = std::nullopt) {
  lua_State* L = kw.state();
  const int type = kw.push("tau_p");
  const bool infinite = type == LUA_TNUMBER && lua_tonumber(L, -1) == HUGE_VAL;
  lua_pop(L, 1);
  if (infinite) return HUGE_VAL;
  return fallback ? kw.number("tau_p", *fallback, Range::non_negative())
                  : kw.number("tau_p", Range::non_negative());
}

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
  const NumberOrRamp kT = kw_number_or_ramp(kw, "kT", Range::non_negative());
  kw.finish();
  auto method =
      engine_call("Langevin", [&] { return Method::langevin(group->sites, gamma, kT.value); });
  engine_call("Langevin", [&] { method->set_kT_ramp(kT.ramp); });
  push_method(L, "Langevin", std::move(group), std::move(method));
  return 1;
}

int l_active(lua_State* L) {
  Kwargs kw(L, 1, "Active");
  auto group = kw_group(kw, "group");
  const double gamma = kw.number("gamma", 0.2, Range::non_negative());
  const NumberOrRamp f0 = kw_number_or_ramp(kw, "f0", Range::non_negative());
  const double tau_p = kw_tau_p(kw);
  const NumberOrRamp kT = kw_number_or_ramp(kw, "kT", Range::non_negative(), 0.0);
  const bool randomize = kw.boolean("randomize", true);
  kw.finish();
  auto method = engine_call(
      "Active", [&] { return Method::active(group->sites, gamma, f0.value, tau_p, kT.value); });
  engine_call("Active", [&] {
    method->set_f0_ramp(f0.ramp);
    method->set_kT_ramp(kT.ramp);
  });
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

// m:set{gamma =, kT =, f0 =, tau_p =}: changes parameters between runs (each key optional;
// kT and f0 take numbers or ramps; Damped has only gamma, Langevin no f0 or tau_p).
int l_set(lua_State* L) {
  MethodHandle& m = check<MethodHandle>(L, 1);
  Kwargs kw(L, 2, m.kind + ":set");
  Method& method = *m.method;
  MethodParams p = method.params();
  p.gamma = kw.number("gamma", p.gamma, Range::non_negative());
  std::optional<NumberOrRamp> kT, f0;
  if (m.kind != "Damped" && kw.has("kT")) kT = kw_number_or_ramp(kw, "kT", Range::non_negative());
  if (m.kind == "Active") {
    if (kw.has("f0")) f0 = kw_number_or_ramp(kw, "f0", Range::non_negative());
    p.tau_p = kw_tau_p(kw, p.tau_p);
  }
  kw.finish();
  if (kT) p.kT = kT->value;
  if (f0) p.f0 = f0->value;
  engine_call(kw.owner(), [&] {
    p.validate();
    method.params() = p;
    if (kT) method.set_kT_ramp(kT->ramp);
    if (f0) method.set_f0_ramp(f0->ramp);
  });
  return 0;
}

const luaL_Reg kMethods[] = {
    {"set", &lua_wrap<&l_set>},       {"kind", &lua_wrap<&l_kind>}, {"group", &lua_wrap<&l_group>},
    {"params", &lua_wrap<&l_params>}, {nullptr, nullptr},
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
