// invasim.Lipolysis{rate =, floor =}: adipocytes that shrink while cancer cells touch them
// (integrate/lipolysis.hpp; docs/model.md, Bodies, "Lipolysis"):
//   lip:touched(sys) -> {true, false, ...}   per adipocyte, in sys:adipocytes() order
//   lip:apply(sys, elapsed) -> n             shrinks the touched ones by `elapsed` time
//   lip:params() -> {rate =, floor =}
// During a run, sim:lipolysis(lip, {every = N}) applies it every N steps (bind_simulation.cpp).
#include <lua.hpp>

#include "core/names.hpp"
#include "lua/adapters.hpp"
#include "lua/engine_fields.hpp"
#include "lua/fields.hpp"
#include "lua/module.hpp"

namespace invasim::lua {

namespace {

const FieldTable<LipolysisParams>& lipolysis_fields() {
  using P = LipolysisParams;
  static const FieldTable<P> table(
      "Lipolysis",
      {
          required(number<P>("rate", &P::rate, Range::non_negative(), "1/tau",
                             "fraction of an adipocyte's initial reference volume lost per "
                             "unit time while a cancer cell touches it")),
          number<P>("floor", &P::floor, Range{0.0, 1.0, true, false}, "1",
                    "smallest reference volume, as a fraction of the initial one"),
      });
  return table;
}

}  // namespace

std::string LuaType<Lipolysis>::describe(const Lipolysis& l) {
  return lipolysis_fields().describe(l.params());
}

namespace {

// lip:touched(sys) -> {true, false, ...}: whether a cancer cell touches each adipocyte now.
int l_touched(lua_State* L) {
  const Lipolysis& lip = check<Lipolysis>(L, 1);
  const SystemHandle& sim = check<SystemHandle>(L, 2);
  const std::vector<char> touched =
      engine_call("Lipolysis:touched", [&] { return lip.touched(sim.system); });
  return push_results(L, 1, [&touched](lua_State* S) noexcept {
    push_list(S, touched.size(), [&](std::size_t b) { lua_pushboolean(S, touched[b] != 0); });
    return 1;
  });
}

// lip:apply(sys, elapsed) -> the number of adipocytes touched (and shrunk, above their floor).
int l_apply(lua_State* L) {
  const Lipolysis& lip = check<Lipolysis>(L, 1);
  SystemHandle& sim = check<SystemHandle>(L, 2);
  const double elapsed = arg_number(L, 3);
  const int n = engine_call("Lipolysis:apply", [&] { return lip.apply(sim.system, elapsed); });
  sim.changed();
  lua_pushinteger(L, n);
  return 1;
}

}  // namespace

void open_lipolysis(lua_State* L) {
  define_params_type<Lipolysis, &lipolysis_fields, [](const Lipolysis& l) { return l.params(); },
                     [](const LipolysisParams& p) { return std::make_shared<Lipolysis>(p); }>(
      L, {INVASIM_LUA_FN(touched), INVASIM_LUA_FN(apply)});
}

}  // namespace invasim::lua
