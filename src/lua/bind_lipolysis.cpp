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

void open_lipolysis(lua_State* L) {
  define_params_type<Lipolysis, &lipolysis_fields, [](const Lipolysis& l) { return l.params(); },
                     [](const LipolysisParams& p) { return std::make_shared<Lipolysis>(p); }>(
      L, {// lip:touched(sys) -> {true, false, ...}: whether a cancer cell touches each adipocyte
          method<"touched",
                 [](const Lipolysis& lip, const SystemHandle& sim) {
                   const std::vector<char> touched = lip.touched(sim.system);
                   return std::vector<bool>(touched.begin(), touched.end());
                 }>(),
          // lip:apply(sys, elapsed) -> the number of adipocytes touched (and shrunk, above
          // their floor)
          method<"apply", [](const Lipolysis& lip, SystemHandle& sim, double elapsed) {
            const int n = lip.apply(sim.system, elapsed);
            sim.changed();
            return n;
          }>()});
}

}  // namespace invasim::lua
