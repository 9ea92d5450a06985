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

#include "core/names.hpp"
#include "lua/adapters.hpp"
#include "lua/engine_fields.hpp"
#include "lua/module.hpp"

namespace invasim::lua {

namespace {

// The keys of the three method constructors: the engine's MethodParams (their defaults) and
// what a constructor takes besides (the group, ramps, randomize).
struct MethodKeys : MethodParams {
  std::shared_ptr<Group> group;
  std::optional<Ramp> kT_ramp, f0_ramp;
  bool randomize = true;
};

using K = MethodKeys;

Field<K> gamma_field() {
  return number<K>("gamma", &K::gamma, Range::non_negative(), "sqrt(m eps_c)/sigma",
                   "damping coefficient: force -gamma v");
}
Field<K> kT_field() {
  return number_or_ramp<K>("kT", &K::kT, &K::kT_ramp, Range::non_negative(), "eps_c",
                           "temperature of the thermal noise");
}
Field<K> group_of_method() {
  return group_field<K>(&K::group, "the sites this method moves (sys:group(name))");
}

const FieldTable<K>& damped_fields() {
  static const FieldTable<K> table("Damped", {group_of_method(), gamma_field()});
  return table;
}

const FieldTable<K>& langevin_fields() {
  static const FieldTable<K> table("Langevin",
                                   {group_of_method(), gamma_field(), required(kT_field())});
  return table;
}

// Active also lists every MethodParams field: it is the table m:params() reports for any kind.
const FieldTable<K>& active_fields() {
  static const FieldTable<K> table(
      "Active",
      {
          group_of_method(),
          gamma_field(),
          kT_field(),
          required(number_or_ramp<K>("f0", &K::f0, &K::f0_ramp, Range::non_negative(),
                                     "eps_c/sigma", "self-propulsion force")),
          required(number<K>("tau_p", &K::tau_p, Range::non_negative(), "tau",
                             "persistence time of the orientation (0: white noise; inf, math.huge "
                             "in Lua: frozen orientations)",
                             /*allow_infinity=*/true)),
          option(boolean<K>("randomize", &K::randomize,
                            "give the group random orientations at creation")),
      });
  return table;
}

const FieldTable<K>& fields_of(const std::string& kind) {
  if (kind == "Damped") return damped_fields();
  if (kind == "Langevin") return langevin_fields();
  return active_fields();
}

// The keys as a handle holds them.
K keys_of(const MethodHandle& m) {
  K k;
  static_cast<MethodParams&>(k) = m.method->params();
  k.group = m.group;
  k.kT_ramp = m.method->kT_ramp();
  k.f0_ramp = m.method->f0_ramp();
  return k;
}

}  // namespace

std::string LuaType<MethodHandle>::describe(const MethodHandle& m) {
  return cat(m.kind, "(group '", m.group->name, "' of ", m.group->sites.size(), " sites, ",
             fields_of(m.kind).describe_fields(keys_of(m)), ")");
}

namespace {

void push_method(lua_State* L, const char* kind, std::shared_ptr<Group> group,
                 std::shared_ptr<Method> method) {
  push(L, std::make_shared<MethodHandle>(MethodHandle{kind, std::move(method), std::move(group)}));
}

int l_damped(lua_State* L) {
  Kwargs kw(L, 1, "Damped");
  K k = damped_fields().make(kw);
  auto method = engine_call("Damped", [&] { return Method::damped(k.group->sites, k.gamma); });
  push_method(L, "Damped", std::move(k.group), std::move(method));
  return 1;
}

int l_langevin(lua_State* L) {
  Kwargs kw(L, 1, "Langevin");
  K k = langevin_fields().make(kw);
  auto method =
      engine_call("Langevin", [&] { return Method::langevin(k.group->sites, k.gamma, k.kT); });
  engine_call("Langevin", [&] { method->set_kT_ramp(k.kT_ramp); });
  push_method(L, "Langevin", std::move(k.group), std::move(method));
  return 1;
}

int l_active(lua_State* L) {
  Kwargs kw(L, 1, "Active");
  K k = active_fields().make(kw);
  auto method = engine_call(
      "Active", [&] { return Method::active(k.group->sites, k.gamma, k.f0, k.tau_p, k.kT); });
  engine_call("Active", [&] {
    method->set_f0_ramp(k.f0_ramp);
    method->set_kT_ramp(k.kT_ramp);
  });
  if (k.randomize) {
    SystemHandle& sim = owner_of(k.group->owner, "Active: group '" + k.group->name + "'",
                                 "make groups with sys:group(name)");
    method->randomize_orientations(sim.system, sim.system.step);
    sim.changed();
  }
  push_method(L, "Active", std::move(k.group), std::move(method));
  return 1;
}

// m:params() -> {gamma =, kT =, f0 =, tau_p =}: the Method's MethodParams, whatever its kind.
// m:set{gamma =, kT =, f0 =, tau_p =}: changes parameters between runs (each key optional;
// kT and f0 take numbers or ramps; Damped has only gamma, Langevin no f0 or tau_p).
int l_set(lua_State* L) {
  MethodHandle& m = check<MethodHandle>(L, 1);
  Kwargs kw(L, 2, m.kind + ":set");
  const bool kT_given = m.kind != "Damped" && kw.has("kT");
  const bool f0_given = m.kind == "Active" && kw.has("f0");
  K k = keys_of(m);
  fields_of(m.kind).set(kw, k);
  Method& method = *m.method;
  engine_call(kw.owner(), [&] {
    const MethodParams& p = k;
    p.validate();
    method.params() = p;
    if (kT_given) method.set_kT_ramp(k.kT_ramp);
    if (f0_given) method.set_f0_ramp(k.f0_ramp);
  });
  return 0;
}

}  // namespace

void open_method(lua_State* L) {
  define_type<MethodHandle>(
      L, {INVASIM_LUA_FN(set),
          getter<MethodHandle, [](const MethodHandle& m) { return m.kind; }>("kind"),
          getter<MethodHandle, [](const MethodHandle& m) { return m.group; }>("group"),
          params_method<MethodHandle, &active_fields, &keys_of>("params")});
  set_constructor(L, "Damped", &lua_wrap<&l_damped>, damped_fields().infos());
  set_constructor(L, "Langevin", &lua_wrap<&l_langevin>, langevin_fields().infos());
  set_constructor(L, "Active", &lua_wrap<&l_active>, active_fields().infos());
}

}  // namespace invasim::lua
