#pragma once
// Field builders for the engine's own value types (fields.hpp): a number or an invasim.ramp{},
// a Group, and the FIRE settings shared by Fire, sys:compress and sys:rescale.
#include <memory>
#include <optional>

#include "lua/adapters.hpp"
#include "lua/engine_types.hpp"
#include "lua/fields.hpp"

namespace invasim::lua {

// A number or an invasim.ramp{} (kT, f0, P): `value` receives the number or the ramp's start,
// `ramp` the ramp (cleared by a number). Range applies to the number and to both ramp ends.
template <typename P, typename Value, typename RampSlot>
Field<P> number_or_ramp(std::string name, Value value, RampSlot ramp, Range range, std::string unit,
                        std::string help) {
  Field<P> f;
  f.info = field_declaration(name, {"number", "Ramp"}, shown_range(range, false), std::move(unit),
                             std::move(help));
  f.read = [name, value, ramp, range](Kwargs& kw, P& p, bool required) {
    if (!required && !kw.has(name)) return;
    const NumberOrRamp v = kw_number_or_ramp(kw, name, range);
    std::invoke(value, p) = v.value;
    std::invoke(ramp, p) = v.ramp;
  };
  f.value = [value](const P& p) -> std::optional<ParamValue> {
    return std::invoke(value, const_cast<P&>(p));
  };
  return f;
}

// The Group a method or correlator moves or measures (required; not part of the state).
template <typename P>
Field<P> group_field(std::shared_ptr<Group> P::*slot, std::string help) {
  Field<P> f;
  f.info = field_declaration("group", {"Group"}, std::nullopt, "", std::move(help));
  f.info.required = true;
  f.info.state = false;
  f.read = [slot](Kwargs& kw, P& p, bool required) {
    if (auto g = kw_group(kw, "group", required)) p.*slot = std::move(g);
  };
  return f;
}

// The FIRE keys ftol, dt, dt_max, max_steps of the FireParams that `fire` selects in P.
template <typename P, typename Access>
std::vector<Field<P>> fire_fields(Access fire) {
  const auto at = [fire](auto member) {
    return [ fire, member ](P & p) -> auto& {
      return std::invoke(fire, p).*member;
    };
  };
  return {
      number<P>("ftol", at(&FireParams::ftol), Range::positive(), "eps/sigma",
                "FIRE: converged when the largest force per site is below ftol"),
      number<P>("dt", at(&FireParams::dt), Range::positive(), "tau", "FIRE: initial time step"),
      number<P>("dt_max", at(&FireParams::dt_max), Range::positive(), "tau",
                "FIRE: largest time step"),
      integer<P>("max_steps", at(&FireParams::max_steps), Range::non_negative(), "1",
                 "FIRE: iterations before giving up (not converged)"),
  };
}

namespace detail {
template <auto Table, auto Make>
int construct_from_fields(lua_State* L) {
  Kwargs kw(L, 1, Table().type());
  const auto params = Table().make(kw);
  push(L, engine_call(Table().type(), [&] { return Make(params); }));
  return 1;
}
}  // namespace detail

// Binds a type T whose parameters are one FieldTable: its methods plus obj:params() (the
// table's keys read from ParamsOf(obj)), and the constructor invasim.<Table().type()>{...},
// which reads the keys and builds the object with Make(params) (a std::shared_ptr<T>).
template <typename T, auto Table, auto ParamsOf, auto Make>
void define_params_type(lua_State* L, std::initializer_list<luaL_Reg> methods) {
  RegList list(methods);
  list.add(params_method<T, Table, ParamsOf>("params"));
  define_type<T>(L, list.data());
  set_constructor(L, Table().type().c_str(), &lua_wrap<&detail::construct_from_fields<Table, Make>>,
                  Table().infos());
}

}  // namespace invasim::lua
