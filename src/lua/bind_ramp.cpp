// Ramps, the parameter type that changes linearly over a run:
//   invasim.ramp{from =, to =, steps =}   -> Ramp
// accepted wherever a method or the pressure wall takes kT, f0 or P (Langevin{kT = ...},
// Active{f0 = ...}, dyn:pressure_wall{P = ...}, m:set{...}, dyn:set_pressure(...)). The ramp
// starts at the first step it is used in; after `steps` steps it stays at `to`.
#include <lua.hpp>

#include <limits>

#include "core/names.hpp"
#include "lua/adapters.hpp"
#include "lua/engine_types.hpp"
#include "lua/fields.hpp"
#include "lua/module.hpp"

namespace invasim::lua {

std::string LuaType<Ramp>::describe(const Ramp& r) {
  return cat("Ramp(from=", r.from, ", to=", r.to, ", steps=", r.steps, ")");
}

NumberOrRamp kw_number_or_ramp(Kwargs& kw, std::string_view key, Range range,
                               std::optional<double> fallback) {
  lua_State* L = kw.state();
  const int type = kw.push(key);
  if (type == LUA_TUSERDATA) {
    auto* ramp = test<Ramp>(L, -1);
    if (!ramp || !*ramp)
      fail_input(kw.owner(), ": key '", key, "' must be a number or an invasim.ramp{}, got ",
                 type_name_at(L, -1));
    lua_pop(L, 1);
    const Ramp& r = **ramp;
    for (const double end : {r.from, r.to})
      if (!range.contains(end))
        fail_input(kw.owner(), ": key '", key, "': ramp end ", end, " is out of range (must be ",
                   range.describe(), ")");
    return {r.from, r};
  }
  lua_pop(L, 1);
  if (fallback) return {kw.number(key, *fallback, range), std::nullopt};
  return {kw.number(key, range), std::nullopt};
}

namespace {

// The keys of invasim.ramp{} (all required).
const FieldTable<Ramp>& ramp_fields() {
  static const FieldTable<Ramp> table(
      "ramp", {
                  required(number<Ramp>("from", &Ramp::from, Range{}, "", "value at the start")),
                  required(number<Ramp>("to", &Ramp::to, Range{}, "", "value after `steps`")),
                  required(integer<Ramp>("steps", &Ramp::steps, Range::at_least(1), "steps",
                                         "length of the ramp in time steps")),
              });
  return table;
}

int l_ramp(lua_State* L) {
  Kwargs kw(L, 1, "ramp");
  const Ramp r = ramp_fields().make(kw);
  r.validate("ramp");
  push(L, std::make_shared<Ramp>(r));
  return 1;
}

}  // namespace

void open_ramp(lua_State* L) {
  define_type<Ramp>(L,
                    {// r:value(k): the value k steps after the ramp's start
                     method<"value",
                            [](const Ramp& ramp, std::uint64_t k) {
                              Ramp r = ramp;
                              r.start = 0;
                              return r.value(k);
                            }>(),
                     params_method<Ramp, &ramp_fields, [](const Ramp& r) { return r; }>("params")});
  set_constructor(L, "ramp", &lua_wrap<&l_ramp>, ramp_fields().infos());
}

}  // namespace invasim::lua
