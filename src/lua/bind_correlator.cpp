// Time correlation functions of a group, sampled by the production stage every `every`
// steps (measure/time_correlator.hpp):
//   local c = invasim.Correlator{group =, interval =, lags = 100, origin_every = 1,
//                                k = 2 pi, fs_average = "isotropic" | "yz",
//                                velocity = true, orientation = true, position = true}
//   c:sample(sys)        -- interval = time between samples (every * dt)
//   c:result()           -- {names = {"t", ...}, columns = {t = {...}, cvv = {...}, ...}}
//   c:tau_d(), c:tau_d_standard(), c:tau_r()   -- nil when not reached
//   c:samples()
#include <lua.hpp>

#include <cmath>

#include "lua/checkpoint_parts.hpp"
#include "lua/engine_types.hpp"
#include "lua/module.hpp"
#include "lua/names.hpp"
#include "measure/time_correlator.hpp"

namespace invasim::lua {

// A correlator and the System its group belongs to.
struct CorrelatorHandle {
  TimeCorrelator correlator;
  std::shared_ptr<Group> group;
};

template <>
struct LuaType<CorrelatorHandle> {
  static constexpr const char* name = "Correlator";
  static constexpr const char* metatable = "invasim.Correlator";
  static std::string describe(const CorrelatorHandle& c) {
    return cat("Correlator(group '", c.group->name, "' of ", c.group->sites.size(), " sites, ",
               c.correlator.params().lags, " lags, ", c.correlator.samples(), " samples)");
  }
};

namespace {

int l_new(lua_State* L) {
  Kwargs kw(L, 1, "Correlator");
  auto group = kw_group(kw, "group");
  TimeCorrelatorParams p;
  p.sample_interval = kw.number("interval", Range::greater_than(0));
  p.lags = kw.integer<int>("lags", p.lags, Range::at_least(1));
  p.origin_every = kw.integer<int>("origin_every", p.origin_every, Range::at_least(1));
  p.k = kw.number("k", p.k, Range::greater_than(0));
  p.fs_average = kw.choice("fs_average", {"isotropic", "yz"}, std::string("isotropic")) == "yz"
                     ? FsAverage::kAxesYZ
                     : FsAverage::kIsotropic;
  p.velocity = kw.boolean("velocity", p.velocity);
  p.orientation = kw.boolean("orientation", p.orientation);
  p.position = kw.boolean("position", p.position);
  kw.finish();
  if (group->sites.empty()) fail_input("Correlator: group '", group->name, "' is empty");
  auto handle = engine_call("Correlator", [&] {
    return std::make_shared<CorrelatorHandle>(
        CorrelatorHandle{TimeCorrelator(group->sites, p), group});
  });
  push(L, std::move(handle));
  return 1;
}

int l_sample(lua_State* L) {
  CorrelatorHandle& c = check<CorrelatorHandle>(L, 1);
  const Simulation& sim = check<Simulation>(L, 2);
  require_same_system(*c.group, sim, "sample");
  engine_call("sample", [&] { c.correlator.sample(sim.system); });
  return 0;
}

int l_result(lua_State* L) {
  const Columns cols = check<CorrelatorHandle>(L, 1).correlator.columns();
  return push_results(L, 1, [&cols](lua_State* S) noexcept {
    lua_createtable(S, 0, 2);
    lua_createtable(S, int(cols.names.size()), 0);
    for (std::size_t j = 0; j < cols.names.size(); ++j) {
      lua_pushstring(S, cols.names[j].c_str());
      lua_rawseti(S, -2, lua_Integer(j + 1));
    }
    lua_setfield(S, -2, "names");
    lua_createtable(S, 0, int(cols.names.size()));
    for (std::size_t j = 0; j < cols.names.size(); ++j) {
      push_number_list(S, cols.values[j].data(), cols.values[j].size());
      lua_setfield(S, -2, cols.names[j].c_str());
    }
    lua_setfield(S, -2, "columns");
    return 1;
  });
}

void push_optional(lua_State* L, const std::optional<double>& v) {
  if (v)
    lua_pushnumber(L, *v);
  else
    lua_pushnil(L);
}

int l_tau_d(lua_State* L) {
  push_optional(L, check<CorrelatorHandle>(L, 1).correlator.tau_d());
  return 1;
}
int l_tau_d_standard(lua_State* L) {
  push_optional(L, check<CorrelatorHandle>(L, 1).correlator.tau_d_standard());
  return 1;
}
int l_tau_r(lua_State* L) {
  push_optional(L, check<CorrelatorHandle>(L, 1).correlator.tau_r());
  return 1;
}
int l_samples(lua_State* L) {
  lua_pushinteger(L, lua_Integer(check<CorrelatorHandle>(L, 1).correlator.samples()));
  return 1;
}

const luaL_Reg kMethods[] = {
    {"sample", &lua_wrap<&l_sample>},
    {"result", &lua_wrap<&l_result>},
    {"tau_d", &lua_wrap<&l_tau_d>},
    {"tau_d_standard", &lua_wrap<&l_tau_d_standard>},
    {"tau_r", &lua_wrap<&l_tau_r>},
    {"samples", &lua_wrap<&l_samples>},
    {nullptr, nullptr},
};

}  // namespace

std::shared_ptr<TimeCorrelator> shared_correlator(lua_State* L, int index) {
  auto* slot = static_cast<std::shared_ptr<CorrelatorHandle>*>(
      luaL_testudata(L, index, LuaType<CorrelatorHandle>::metatable));
  if (!slot || !*slot) return nullptr;
  return std::shared_ptr<TimeCorrelator>(*slot, &(*slot)->correlator);
}

void open_correlator(lua_State* L) {
  define_type<CorrelatorHandle>(L, kMethods);
  lua_pushcfunction(L, &lua_wrap<&l_new>);
  lua_setfield(L, -2, "Correlator");
}

}  // namespace invasim::lua
