// invasim.Tethers{K =}: ECM springs between adipocyte centres (TetherForce), with
// :connect{mean_degree = 6}, :heterogeneity{lambda =} and :list() acting on the System the
// tethers were added to (sys:add(tethers) first).
#include <lua.hpp>

#include "core/names.hpp"
#include "lua/adapters.hpp"
#include "lua/engine_types.hpp"
#include "lua/fields.hpp"
#include "lua/module.hpp"

namespace invasim::lua {

namespace {

// The keys of invasim.Tethers{} (K required: TetherForce has no default).
struct TetherKeys {
  double K = 0.0;
};

const FieldTable<TetherKeys>& tether_fields() {
  static const FieldTable<TetherKeys> table(
      "Tethers", {required(number<TetherKeys>("K", &TetherKeys::K, Range::non_negative(),
                                              "eps_c/sigma^2", "tether spring stiffness"))});
  return table;
}

// The keys of t:connect{} (the engine's connect_by_mean_degree takes the degree without a
// default: this is its one default).
struct ConnectKeys {
  double mean_degree = 6.0;
};

const FieldTable<ConnectKeys>& connect_fields() {
  static const FieldTable<ConnectKeys> table(
      "connect", {number<ConnectKeys>("mean_degree", &ConnectKeys::mean_degree, Range::positive(),
                                      "tethers", "mean number of tethers per adipocyte")});
  return table;
}

}  // namespace

std::string LuaType<Tethers>::describe(const Tethers& t) {
  return cat("Tethers(", tether_fields().describe_fields({t.force->stiffness()}), ", ",
             t.force->tethers().size(), " tethers)");
}

namespace {

int l_new(lua_State* L) {
  Kwargs kw(L, 1, "Tethers");
  const TetherKeys k = tether_fields().make(kw);
  auto force = engine_call("Tethers", [&] { return std::make_shared<TetherForce>(k.K); });
  push(L, std::make_shared<Tethers>(std::move(force)));
  return 1;
}

SystemHandle& system_of(const Tethers& t, const char* method) {
  return owner_of(t.owner, method, "add the tethers to a System first with sys:add(tethers)");
}

// t:connect{mean_degree = 6} -> d_c: tethers the closest pairs of adipocytes (rest lengths =
// current separations) so that each has mean_degree tethers on average.
int l_connect(lua_State* L) {
  Tethers& t = check<Tethers>(L, 1);
  Kwargs kw(L, 2, "connect");
  const double degree = connect_fields().make(kw).mean_degree;
  SystemHandle& sim = system_of(t, "connect");
  const double d_c =
      engine_call("connect", [&] { return t.force->connect_by_mean_degree(sim.system, degree); });
  sim.changed();
  lua_pushnumber(L, d_c);
  return 1;
}

// t:heterogeneity{lambda =}: rest lengths (1 -+ lambda) R below / above the box's mid z.
int l_heterogeneity(lua_State* L) {
  Tethers& t = check<Tethers>(L, 1);
  Kwargs kw(L, 2, "heterogeneity");
  const double lambda = kw.number("lambda", Range::between(0, 1));
  kw.finish();
  SystemHandle& sim = system_of(t, "heterogeneity");
  engine_call("heterogeneity", [&] { t.force->apply_heterogeneity(sim.system, lambda); });
  sim.changed();
  return 0;
}

// t:list() -> {{i =, j =, rest_length =, length =}, ...} in tether order: the two adipocytes
// (1-based, as in sys:adipocytes()), l_ij0 and the current centre separation R_ij (through
// the tether's own image) in the System the tethers act on.
int l_list(lua_State* L) {
  const Tethers& t = check<Tethers>(L, 1);
  const SystemHandle& sim = system_of(t, "list");
  const std::vector<Tether>& tethers = t.force->tethers();
  const std::vector<Vec3> c =
      engine_call("list", [&] { return TetherForce::body_centres(sim.system); });
  const Box& box = sim.system.box();
  std::vector<Record> rows;
  for (const Tether& e : tethers)
    rows.push_back({{"i", e.a + 1},
                    {"j", e.b + 1},
                    {"rest_length", e.rest_length},
                    {"length", TetherForce::separation(box, c, e).norm()}});
  return push_records(L, rows);
}

}  // namespace

void open_tethers(lua_State* L) {
  define_type<Tethers>(
      L, {INVASIM_LUA_FN(connect), INVASIM_LUA_FN(heterogeneity),
          getter<Tethers, [](const Tethers& t) { return t.force->tethers().size(); }>("count"),
          getter<Tethers, [](const Tethers& t) { return t.force->stiffness(); }>("K"),
          method<"set_K",
                 [](Tethers& t, double k) {
                   t.force->set_stiffness(k);
                   if (auto sim = t.owner.lock()) sim->changed();
                 }>(),
          INVASIM_LUA_FN(list)});
  set_constructor(L, "Tethers", &lua_wrap<&l_new>, tether_fields().infos());
  set_method_keys(L, "Tethers", "connect", connect_fields().infos());
}

}  // namespace invasim::lua
