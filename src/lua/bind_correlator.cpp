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

#include "core/names.hpp"
#include "lua/adapters.hpp"
#include "lua/checkpoint_parts.hpp"
#include "lua/engine_fields.hpp"
#include "lua/engine_types.hpp"
#include "lua/module.hpp"
#include "measure/time_correlator.hpp"

namespace invasim::lua {

// A correlator and the System its group belongs to.
struct CorrelatorHandle {
  CorrelatorHandle(const TimeCorrelatorParams& params, std::shared_ptr<Group> of)
      : correlator(of->sites, params), group(std::move(of)) {}
  TimeCorrelator correlator;  // (built in place: it is not moved)
  std::shared_ptr<Group> group;
};

namespace {

// The keys of invasim.Correlator{}; defaults: TimeCorrelatorParams'.
struct CorrelatorKeys : TimeCorrelatorParams {
  std::shared_ptr<Group> group;
};

const FieldTable<CorrelatorKeys>& correlator_fields() {
  using P = CorrelatorKeys;
  static const FieldTable<P> table(
      "Correlator",
      {
          group_field<P>(&P::group, "the sites whose motion is correlated"),
          required(number<P>("interval", &P::sample_interval, Range::greater_than(0), "tau",
                             "time between samples (every * dt)")),
          integer<P>("lags", &P::lags, Range::at_least(1), "samples", "number of lags"),
          integer<P>("origin_every", &P::origin_every, Range::at_least(1), "samples",
                     "samples between time origins"),
          number<P>("k", &P::k, Range::greater_than(0), "1/sigma",
                    "wave number of the self-intermediate scattering function"),
          choice<P>("fs_average", &P::fs_average,
                    {{"isotropic", FsAverage::kIsotropic}, {"yz", FsAverage::kAxesYZ}},
                    "F_s averaged over all directions or over the y and z axes"),
          boolean<P>("velocity", &P::velocity, "velocity autocorrelation"),
          boolean<P>("orientation", &P::orientation, "orientation autocorrelation"),
          boolean<P>("position", &P::position, "MSD and F_s(k, t)"),
      });
  return table;
}

}  // namespace

INVASIM_LUA_TYPE(CorrelatorHandle, "Correlator");
std::string LuaType<CorrelatorHandle>::describe(const CorrelatorHandle& c) {
  return cat("Correlator(group '", c.group->name, "' of ", c.correlator.group().size(), " sites, ",
             c.correlator.params().lags, " lags, ", c.correlator.samples(), " samples)");
}

namespace {

int l_new(lua_State* L) {
  Kwargs kw(L, 1, "Correlator");
  CorrelatorKeys k = correlator_fields().make(kw);
  std::shared_ptr<Group> group = std::move(k.group);
  const TimeCorrelatorParams& p = k;
  if (group->sites.empty()) fail_input("Correlator: group '", group->name, "' is empty");
  auto handle =
      engine_call("Correlator", [&] { return std::make_shared<CorrelatorHandle>(p, group); });
  push(L, std::move(handle));
  return 1;
}

// c:params() -> {interval =, lags =, origin_every =, k =, fs_average =, velocity =, ...}
int l_params(lua_State* L) {
  CorrelatorKeys k;
  static_cast<TimeCorrelatorParams&>(k) = check<CorrelatorHandle>(L, 1).correlator.params();
  correlator_fields().push_params(L, k);
  return 1;
}

int l_result(lua_State* L) {
  const Columns cols = check<CorrelatorHandle>(L, 1).correlator.columns();
  Record columns;
  for (std::size_t j = 0; j < cols.names.size(); ++j)
    columns.push_back({cols.names[j], cols.values[j]});
  return push_record(L, {{"names", cols.names}, {"columns", std::move(columns)}});
}

}  // namespace

std::shared_ptr<TimeCorrelator> shared_correlator(lua_State* L, int index) {
  auto* slot = test<CorrelatorHandle>(L, index);
  if (!slot || !*slot) return nullptr;
  return std::shared_ptr<TimeCorrelator>(*slot, &(*slot)->correlator);
}

void open_correlator(lua_State* L) {
  define_type<CorrelatorHandle>(
      L,
      {method<"sample",
              [](CorrelatorHandle& c, const SystemHandle& sim) {
                require_same_system(*c.group, sim, "sample");
                c.correlator.sample(sim.system);
              }>(),
       INVASIM_LUA_FN(result),
       getter<CorrelatorHandle, [](const CorrelatorHandle& c) { return c.correlator.tau_d(); }>(
           "tau_d"),
       getter<CorrelatorHandle,
              [](const CorrelatorHandle& c) { return c.correlator.tau_d_standard(); }>(
           "tau_d_standard"),
       getter<CorrelatorHandle, [](const CorrelatorHandle& c) { return c.correlator.tau_r(); }>(
           "tau_r"),
       getter<CorrelatorHandle, [](const CorrelatorHandle& c) { return c.correlator.samples(); }>(
           "samples"),
       INVASIM_LUA_FN(params)});
  set_constructor(L, "Correlator", &lua_wrap<&l_new>, correlator_fields().infos());
}

}  // namespace invasim::lua
