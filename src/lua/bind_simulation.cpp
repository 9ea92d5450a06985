// invasim.Simulation{system = sys, dynamics = dyn}: a run with scheduled operations
// (run/simulation.hpp; docs/lua.md, "Simulation"). Each operation takes a schedule
// {every = N, phase = 0, at = {steps}, at_end = false, on_stop = false} (at least one):
//   sim:sample(correlator, schedule)          -- correlator sampler
//   sim:snapshots(snapshots, schedule)        -- snapshot writer (an invasim.Snapshots)
//   sim:checkpoint{path =, tethers =, correlator =, extra = function() return "" end,
//                  run_id =, run_parameters =, written = function(step) end, <schedule>}
//   sim:observe(function(step, time) end, schedule)   -- an observer written in Lua
//   sim:lipolysis(lipolysis, {every = N, since = S})  -- adipocytes shrinking where cells
//                                                        touch them
//   sim:run(n [, {progress = p}]) -> steps done, stop signal name or nil
//   sim:operations() -> {"correlator sampler: every 20 steps", ...}
#include <lua.hpp>

#include <cmath>
#include <limits>

#include "core/stop_request.hpp"

#include "core/names.hpp"
#include "lua/checkpoint_parts.hpp"
#include "lua/engine_types.hpp"
#include "lua/function_operation.hpp"
#include "lua/module.hpp"
#include "run/operations.hpp"

namespace invasim::lua {

// The Lua object: the engine Simulation, the objects it runs, and its Lua operations (told
// which Lua thread runs them).
struct SimulationHandle {
  SimulationHandle(std::shared_ptr<SystemHandle> s, std::shared_ptr<DynamicsHandle> d)
      : system(std::move(s)), dyn(std::move(d)), run(make_simulation(system, dyn)) {}
  std::shared_ptr<SystemHandle> system;
  std::shared_ptr<DynamicsHandle> dyn;
  invasim::Simulation run;
  std::vector<std::shared_ptr<LuaFunctionOperation>> lua_ops;
};

INVASIM_LUA_TYPE(SimulationHandle, "Simulation");
std::string LuaType<SimulationHandle>::describe(const SimulationHandle& s) {
  return cat("Simulation(", s.run.operations().size(), " operations, step ", s.system->system.step,
             ")");
}

namespace {

// The schedule keys of kw: every, phase, at, at_end, on_stop (at least one).
Trigger kw_trigger(Kwargs& kw) {
  lua_State* L = kw.state();
  Trigger t;
  bool any = false;
  const auto every = kw.maybe_integer<std::uint64_t>("every", Range::at_least(1));
  const auto phase = kw.maybe_integer<std::uint64_t>("phase", Range::at_least(0));
  if (phase && !every) fail_input(kw.owner(), ": key 'phase' needs key 'every'");
  if (every) {
    if (phase && *phase >= *every)
      fail_input(kw.owner(), ": phase = ", *phase, " must be in [0, ", *every,
                 ") for every = ", *every);
    t |= Trigger::every(*every, phase.value_or(0));
    any = true;
  }
  const int type = kw.push("at");
  if (type != LUA_TNIL) {
    if (type != LUA_TTABLE)
      fail_input(kw.owner(), ": key 'at' must be a list of steps, got ", type_name_at(L, -1));
    std::vector<std::uint64_t> steps;
    const auto n = lua_rawlen(L, -1);
    if (n == 0) fail_input(kw.owner(), ": key 'at' lists no step (an operation that never runs)");
    for (lua_Unsigned i = 1; i <= n; ++i) {
      lua_rawgeti(L, -1, static_cast<lua_Integer>(i));
      if (!lua_isinteger(L, -1) || lua_tointeger(L, -1) < 0)
        fail_input(kw.owner(), ": key 'at[", i, "]' must be an integer step >= 0, got ",
                   lua_type(L, -1) == LUA_TNUMBER ? cat(lua_tonumber(L, -1))
                                                  : std::string(type_name_at(L, -1)));
      steps.push_back(static_cast<std::uint64_t>(lua_tointeger(L, -1)));
      lua_pop(L, 1);
    }
    t |= Trigger::at(std::move(steps));
    any = true;
  }
  lua_pop(L, 1);
  if (kw.boolean("at_end", false)) t |= Trigger::at_end(), any = true;
  if (kw.boolean("on_stop", false)) t |= Trigger::on_stop(), any = true;
  if (!any) kw.finish();  // an unknown key (a misspelt schedule) is the better message
  if (!any)
    fail_input(kw.owner(),
               ": no schedule; give at least one of every = N, at = {steps}, at_end = true, "
               "on_stop = true");
  return t;
}

int l_new(lua_State* L) {
  Kwargs kw(L, 1, "Simulation");
  auto system = kw_object<SystemHandle>(kw, "system", true);
  auto dyn = kw_object<DynamicsHandle>(kw, "dynamics", true);
  kw.finish();
  // The methods added so far move this System's sites (run_steps checks those added later).
  for (const auto& m : dyn->methods)
    require_same_system(*m->group, *system, "Simulation: " + m->kind);
  push(L, std::make_shared<SimulationHandle>(std::move(system), std::move(dyn)));
  return 1;
}

// The schedule table at `index` as a trigger (`what` names the method in messages).
Trigger schedule_arg(lua_State* L, int index, const char* what) {
  Kwargs kw(L, index, what);
  Trigger t = kw_trigger(kw);
  kw.finish();
  return t;
}

// Adds `op` to the run of `s` on the schedule table at argument 3; `what` names the method.
int add_scheduled(lua_State* L, SimulationHandle& s, std::shared_ptr<Operation> op,
                  const char* what) {
  const Trigger t = schedule_arg(L, 3, what);
  engine_call(what, [&] { s.run.add(std::move(op), t); });
  return 0;
}

// sim:sample(correlator, {every = N [, phase = P]}): a correlator samples at equal intervals,
// its own (N x dt), once per step; a schedule that cannot give them is refused here, not at
// the first sample that comes at the wrong time.
int l_sample(lua_State* L) {
  SimulationHandle& s = check<SimulationHandle>(L, 1);
  auto correlator = shared_correlator(L, 2);
  if (!correlator) throw InputError(bad_argument(L, 2, "Correlator"));
  const Trigger t = schedule_arg(L, 3, "sample");
  if (!t.only_periodic())
    fail_input(
        "sample: a correlator samples at equal intervals: its schedule is {every = N} "
        "(and a phase) alone, not ",
        t.describe());
  const double interval = correlator->params().sample_interval;
  const double dt = s.dyn->dynamics.dt();
  if (std::abs(double(t.period()) * dt - interval) > 1e-3 * interval)
    fail_input("sample: every = ", t.period(), " steps of dt = ", dt, " is ",
               double(t.period()) * dt, ", not the correlator's interval ", interval,
               ": make them equal (every = ", interval / dt, ")");
  for (const auto& op : s.run.operations()) {
    const auto* sampler = dynamic_cast<const CorrelatorSampler*>(op.operation.get());
    if (sampler && &sampler->correlator() == correlator.get())
      fail_input("sample: this correlator is sampled by this Simulation already (",
                 op.trigger.describe(), "): twice would sample it twice per interval");
  }
  engine_call("sample", [&] { s.run.add(std::make_shared<CorrelatorSampler>(correlator), t); });
  return 0;
}

// sim:<what>(object, {every = N, since = S}): the operation Op(object, N, S) at the steps
// that are multiples of N, before the operations added after it at the same step. S (default:
// the System's step now) is where its time starts: a resumed run gives its first run's S.
template <typename T, typename Op>
int add_every(lua_State* L, const char* what) {
  SimulationHandle& s = check<SimulationHandle>(L, 1);
  if (!is<T>(L, 2)) throw InputError(bad_argument(L, 2, LuaType<T>::name));
  std::shared_ptr<const T> object = check_shared<T>(L, 2);
  Kwargs kw(L, 3, what);
  const auto every = kw.integer<std::uint64_t>("every", Range::at_least(1));
  const auto since = kw.maybe_integer<std::uint64_t>("since", Range::non_negative());
  kw.finish();
  const std::uint64_t start = since.value_or(s.run.system().step);
  engine_call(what, [&] {
    s.run.add(std::make_shared<Op>(std::move(object), every, start), Trigger::every(every, 0));
  });
  return 0;
}

// sim:lipolysis(lipolysis, {every = N, since = S}): an invasim.Lipolysis, N dt of lipolysis
// each time (less the first time if S is not a multiple of N).
int l_lipolysis(lua_State* L) {
  return add_every<Lipolysis, LipolysisOperation>(L, "lipolysis");
}

// sim:proliferation(proliferation, {every = N, since = S}): an invasim.Proliferation, N dt of
// divisions and deaths each time (as lipolysis); the Dynamics' methods follow the cells (a
// daughter joins its parent's method) and groups made before a change are refused afterwards.
int l_proliferation(lua_State* L) {
  return add_every<Proliferation, ProliferationOperation>(L, "proliferation");
}

// sim:snapshots(snapshots, schedule)
int l_snapshots(lua_State* L) {
  SimulationHandle& s = check<SimulationHandle>(L, 1);
  auto writer = check_shared<SnapshotWriter>(L, 2);
  return add_scheduled(L, s, std::make_shared<SnapshotOperation>(writer), "snapshots");
}

// sim:observe(fn, schedule)
int l_observe(lua_State* L) {
  const auto& s = check_shared<SimulationHandle>(L, 1);
  if (lua_type(L, 2) != LUA_TFUNCTION) throw InputError(bad_argument(L, 2, "function"));
  const Trigger t = schedule_arg(L, 3, "observe");
  auto op = std::make_shared<LuaFunctionOperation>(L, 2, s->system, s->dyn, "observer");
  s->lua_ops.push_back(op);
  engine_call("observe", [&] { s->run.add(op, t); });
  return 0;
}

// sim:checkpoint{path =, tethers =, correlator =, contacts =, extra = fn, run_id =,
// run_parameters =, written = fn, <schedule>}: the System and the Dynamics are the Simulation's
// own.
int l_checkpoint(lua_State* L) {
  const auto& s = check_shared<SimulationHandle>(L, 1);
  Kwargs kw(L, 2, "checkpoint");
  const std::string path = kw.string("path");
  require_no_nul(path, "checkpoint: key 'path'");
  CheckpointParts parts = read_checkpoint_parts(kw, false);
  parts.sim = s->system;
  parts.dyn = s->dyn;
  check_checkpoint_parts(parts);
  const auto run_id = kw.maybe_string("run_id");
  const auto run_parameters = kw.maybe_string("run_parameters");
  if (run_parameters && !run_id)
    fail_input("checkpoint: run_parameters without run_id (give the run's identity too)");
  std::shared_ptr<LuaFunctionOperation> extra, written;
  for (const char* key : {"extra", "written"}) {
    if (const int index = kw_function(kw, key)) {
      auto op = std::make_shared<LuaFunctionOperation>(L, index, s->system, s->dyn, key);
      s->lua_ops.push_back(op);
      (std::string(key) == "extra" ? extra : written) = op;
      lua_pop(L, 1);
    }
  }
  const Trigger t = kw_trigger(kw);
  kw.finish();
  // extra() returns the protocol's own state as a string (called on the running thread).
  SimulationHandle* handle = s.get();
  auto compose = [handle, parts, extra, run_id, run_parameters](CheckpointWriter& w) {
    std::string text;
    if (extra) text = extra->call_for_string(handle->run);
    write_checkpoint_parts(w, parts, text, run_id, run_parameters);
  };
  CheckpointOperation::WrittenFn note;
  if (written) note = [handle, written](std::uint64_t) { written->apply(handle->run); };
  engine_call("checkpoint",
              [&] { s->run.add(std::make_shared<CheckpointOperation>(path, compose, note), t); });
  return 0;
}

// sim:run(n [, {progress = p}]) -> steps done, the stop signal's name or nil.
int l_run(lua_State* L) {
  // An owning copy: the observers run Lua, which may collect the Simulation's userdata
  // (its __gc through the debug library) while the run is on the stack.
  const std::shared_ptr<SimulationHandle> s = check_shared<SimulationHandle>(L, 1);
  const long long n = arg_integer(L, 2, 0, std::numeric_limits<long long>::max());
  std::shared_ptr<Progress> progress;
  if (!lua_isnoneornil(L, 3)) {
    Kwargs kw(L, 3, "run");
    progress = kw_object<Progress>(kw, "progress");
    kw.finish();
  }
  for (const auto& op : s->lua_ops) op->set_thread(L);
  RunResult result;
  try {
    result = engine_call("run", [&] { return run_steps(s->run, s->system, *s->dyn, n, progress); });
  } catch (...) {
    for (const auto& op : s->lua_ops) op->set_thread(nullptr);
    throw;
  }
  for (const auto& op : s->lua_ops) op->set_thread(nullptr);
  const char* signal = result.stop_signal ? stop_signal_name(result.stop_signal) : nullptr;
  return push_results(L, 2, [&result, signal](lua_State* S) noexcept {
    lua_pushinteger(S, static_cast<lua_Integer>(result.steps));
    if (signal)
      lua_pushstring(S, signal);
    else
      lua_pushnil(S);
    return 2;
  });
}

// sim:operations() -> {"<name>: <schedule>", ...} in the order they run.
int l_operations(lua_State* L) {
  const SimulationHandle& s = check<SimulationHandle>(L, 1);
  std::vector<std::string> lines;
  for (const auto& op : s.run.operations())
    lines.push_back(op.operation->name() + ": " + op.trigger.describe());
  push_string_list(L, lines);
  return 1;
}

}  // namespace

void open_simulation(lua_State* L) {
  define_type<SimulationHandle>(
      L, {INVASIM_LUA_FN(sample), INVASIM_LUA_FN(lipolysis), INVASIM_LUA_FN(proliferation),
          INVASIM_LUA_FN(snapshots), INVASIM_LUA_FN(observe), INVASIM_LUA_FN(checkpoint),
          INVASIM_LUA_FN(run), INVASIM_LUA_FN(operations)});
  add_functions(L, {{"Simulation", &lua_wrap<&l_new>}});
}

}  // namespace invasim::lua
