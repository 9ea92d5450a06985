// invasim.Proliferation{division_rate =, death_rate =, inhibition_contacts =, separation =}:
// cancer cells that divide and die (integrate/proliferation.hpp; docs/model.md, "Proliferation
// and death"):
//   prolif:contacts(sys) -> {n, ...}   the contacts of each cancer cell now (index order)
//   prolif:params() -> {division_rate =, death_rate =, inhibition_contacts =, separation =}
// During a run, sim:proliferation(prolif, {every = N}) applies it every N steps
// (bind_simulation.cpp).
#include <lua.hpp>

#include "lua/engine_fields.hpp"
#include "lua/module.hpp"

namespace invasim::lua {

namespace {

const FieldTable<ProliferationParams>& proliferation_fields() {
  using P = ProliferationParams;
  static const FieldTable<P> table(
      "Proliferation",
      {
          number<P>("division_rate", &P::division_rate, Range::non_negative(), "1/tau",
                    "divisions per cell per unit time (1/tau_div)"),
          number<P>("death_rate", &P::death_rate, Range::non_negative(), "1/tau",
                    "deaths per cell per unit time"),
          integer<P>("inhibition_contacts", &P::inhibition_contacts, Range::non_negative(), "sites",
                     "contact inhibition: a cell touching at least this many sites "
                     "does not divide (0: off)"),
          number<P>("separation", &P::separation, Range{0.0, 1.0, true, false}, "d",
                    "daughters' centre distance at division, as a fraction of the diameter"),
      });
  return table;
}

}  // namespace

std::string LuaType<Proliferation>::describe(const Proliferation& p) {
  return proliferation_fields().describe(p.params());
}

void open_proliferation(lua_State* L) {
  define_params_type<
      Proliferation, &proliferation_fields, [](const Proliferation& p) { return p.params(); },
      [](const ProliferationParams& p) { return std::make_shared<Proliferation>(p); }>(
      L, {method<"contacts", [](const Proliferation& p, const SystemHandle& sim) {
        return p.contacts(sim.system);
      }>()});
}

}  // namespace invasim::lua
