// Checkpoints of a protocol's state (src/io/checkpoint.hpp, state_checkpoint.hpp):
//   invasim.save_checkpoint(path, {system =, dynamics =, tethers =, correlator =, extra = "",
//                                  run_id = "", run_parameters = ""})
//   local extra = invasim.load_checkpoint(path, {system =, dynamics =, tethers =, correlator =,
//                                                seed =})   -- seed: give the System a new one
//   local id, parameters = invasim.checkpoint_run(path)  -- the run that wrote it (nil, nil if
//                                                          -- it was written outside a run)
//   invasim.interrupted()   -> "SIGINT" / "SIGTERM" once a stop was requested, else nil
// save writes the System (every site array, bit for bit), the Dynamics (time step, method
// parameters and ramp anchors, the pressure wall), the tethers, a correlator's accumulators
// and a string of the protocol's own (`extra`), atomically. load restores them into objects
// built the same way (same protocol, same parameters) and marks the Dynamics prepared, so the
// run continues bit for bit as if it had never stopped. run_id / run_parameters identify the
// run that writes the checkpoint (protocols/lib/run_identity.lua): they go into the sections
// "run.id" and "run.parameters", which --resume compares with the run it continues.
#include <lua.hpp>

#include <optional>

#include "checkpoint/state_checkpoint.hpp"
#include "core/stop_request.hpp"
#include "lua/engine_types.hpp"
#include "lua/module.hpp"
#include "lua/names.hpp"
#include "measure/time_correlator.hpp"

namespace invasim::lua {

// Defined in bind_correlator.cpp.
TimeCorrelator* test_correlator(lua_State* L, int index);

namespace {

// The objects named in a save/load keyword table.
struct Parts {
  std::shared_ptr<Simulation> sim;
  DynamicsHandle* dyn = nullptr;
  std::shared_ptr<Tethers> tethers;
  TimeCorrelator* correlator = nullptr;
};

Parts read_parts(Kwargs& kw) {
  lua_State* L = kw.state();
  Parts p;
  auto object = [&](const char* key, const char* metatable) -> int {
    const int type = kw.push(key);
    if (type == LUA_TNIL) {
      lua_pop(L, 1);
      return 0;
    }
    if (metatable && !luaL_testudata(L, -1, metatable))
      fail_input(kw.owner(), ": key '", key, "' must be a ", metatable + 8, ", got ",
                 type_name_at(L, -1));
    return lua_gettop(L);
  };
  const int s = object("system", LuaType<Simulation>::metatable);
  if (!s) fail_input(kw.owner(), ": missing required key 'system' (a System)");
  p.sim = check_shared<Simulation>(L, s);
  if (const int d = object("dynamics", LuaType<DynamicsHandle>::metatable))
    p.dyn = &check<DynamicsHandle>(L, d);
  if (const int t = object("tethers", LuaType<Tethers>::metatable))
    p.tethers = check_shared<Tethers>(L, t);
  if (const int c = object("correlator", nullptr)) {
    p.correlator = test_correlator(L, c);
    if (!p.correlator)
      fail_input(kw.owner(), ": key 'correlator' must be a Correlator, got ", type_name_at(L, c));
  }
  return p;
}

void put_ramp(std::vector<double>& out, const std::optional<Ramp>& r) {
  out.push_back(r ? 1.0 : 0.0);
  out.push_back(r ? r->from : 0.0);
  out.push_back(r ? r->to : 0.0);
  out.push_back(r ? double(r->steps) : 0.0);
  out.push_back(r && r->start ? 1.0 : 0.0);
  out.push_back(r && r->start ? double(*r->start) : 0.0);
}

std::optional<Ramp> get_ramp(const std::vector<double>& in, std::size_t at) {
  if (in.at(at) == 0.0) return std::nullopt;
  Ramp r;
  r.from = in[at + 1];
  r.to = in[at + 2];
  r.steps = std::uint64_t(in[at + 3]);
  if (in[at + 4] != 0.0) r.start = std::uint64_t(in[at + 5]);
  return r;
}
constexpr std::size_t kRampDoubles = 6;

void write_dynamics(CheckpointWriter& w, const Dynamics& d) {
  w.put_f64("dynamics.dt", d.dt());
  std::vector<double> params, ramps;
  for (const auto& m : d.methods()) {
    const MethodParams& p = m->params();
    params.insert(params.end(), {p.gamma, p.kT, p.f0, p.tau_p, double(m->group().size())});
    put_ramp(ramps, m->kT_ramp());
    put_ramp(ramps, m->f0_ramp());
  }
  w.put_f64s("dynamics.methods", params);
  w.put_f64s("dynamics.ramps", ramps);
  w.put_u64("dynamics.has_wall", d.pressure_wall() ? 1 : 0);
  if (auto wall = d.pressure_wall()) {
    write_pressure_wall(w, *wall);
    std::vector<double> ramp;
    put_ramp(ramp, wall->pressure_ramp);
    w.put_f64s("dynamics.pressure_ramp", ramp);
  }
}

void read_dynamics(const CheckpointReader& r, Dynamics& d) {
  const auto params = r.get_f64s("dynamics.methods");
  const auto ramps = r.get_f64s("dynamics.ramps");
  const auto& methods = d.methods();
  if (params.size() != 5 * methods.size() || ramps.size() != 2 * kRampDoubles * methods.size())
    fail_input("load_checkpoint: the checkpoint's Dynamics has ", params.size() / 5,
               " methods, this one ", methods.size(), " (not the same protocol?)");
  if (bool(r.get_u64("dynamics.has_wall")) != bool(d.pressure_wall()))
    fail_input("load_checkpoint: the checkpoint's Dynamics ",
               d.pressure_wall() ? "has no pressure wall, this one has one"
                                 : "has a pressure wall, this one has none");
  d.set_dt(r.get_f64("dynamics.dt"));
  for (std::size_t k = 0; k < methods.size(); ++k) {
    Method& m = *methods[k];
    if (params[5 * k + 4] != double(m.group().size()))
      fail_input("load_checkpoint: method ", k + 1, " moves ", m.group().size(), " sites here but ",
                 params[5 * k + 4], " in the checkpoint");
    MethodParams p{params[5 * k], params[5 * k + 1], params[5 * k + 2], params[5 * k + 3]};
    p.validate();
    m.params() = p;
    m.set_kT_ramp(get_ramp(ramps, 2 * kRampDoubles * k));
    m.set_f0_ramp(get_ramp(ramps, 2 * kRampDoubles * k + kRampDoubles));
    m.params() = p;  // set_*_ramp resets the value to the ramp's start
  }
  if (auto wall = d.pressure_wall()) {
    read_pressure_wall(r, *wall);
    wall->pressure_ramp = get_ramp(r.get_f64s("dynamics.pressure_ramp"), 0);
  }
}

void write_correlator(CheckpointWriter& w, const TimeCorrelator& c) {
  const CorrelatorState& s = c.state();
  w.put_u64("correlator.samples", s.samples);
  w.put_f64("correlator.last_time", s.last_time);
  w.put_f64s("correlator.velocity", s.velocity);
  w.put_f64s("correlator.orientation", s.orientation);
  w.put_f64s("correlator.position", s.position);
  w.put_u64s("correlator.origins", s.origins);
  w.put_f64s("correlator.sums", s.sums);
}

void read_correlator(const CheckpointReader& r, TimeCorrelator& c) {
  CorrelatorState s;
  s.samples = r.get_u64("correlator.samples");
  s.last_time = r.get_f64("correlator.last_time");
  s.velocity = r.get_f64s("correlator.velocity");
  s.orientation = r.get_f64s("correlator.orientation");
  s.position = r.get_f64s("correlator.position");
  s.origins = r.get_u64s("correlator.origins");
  s.sums = r.get_f64s("correlator.sums");
  c.restore(std::move(s));
}

int l_save(lua_State* L) {
  const std::string path = arg_string(L, 1);
  Kwargs kw(L, 2, "save_checkpoint");
  const Parts p = read_parts(kw);
  const std::string extra = kw.string("extra", "");
  const auto run_id = kw.maybe_string("run_id");
  const auto run_parameters = kw.maybe_string("run_parameters");
  kw.finish();
  if (run_parameters && !run_id)
    fail_input("save_checkpoint: run_parameters without run_id (give the run's identity too)");
  engine_call("save_checkpoint", [&] {
    CheckpointWriter w;
    write_system(w, p.sim->system);
    if (p.dyn) write_dynamics(w, p.dyn->dynamics);
    if (p.tethers) write_tethers(w, *p.tethers->force);
    if (p.correlator) write_correlator(w, *p.correlator);
    w.put_string("extra", extra);
    if (run_id) w.put_string("run.id", *run_id);
    if (run_parameters) w.put_string("run.parameters", *run_parameters);
    w.write(path);
  });
  return 0;
}

int l_load(lua_State* L) {
  const std::string path = arg_string(L, 1);
  Kwargs kw(L, 2, "load_checkpoint");
  const Parts p = read_parts(kw);
  const auto seed = kw.maybe_integer<std::uint64_t>("seed", Range::at_least(0));
  kw.finish();
  std::string extra;
  engine_call("load_checkpoint", [&] {
    const CheckpointReader r = CheckpointReader::read(path);
    System restored = read_system(r);
    Simulation& sim = *p.sim;
    // Groups, methods and forces index the sites: the System must be built the same way.
    if (restored.n_sites() != sim.system.n_sites() ||
        restored.bodies().size() != sim.system.bodies().size())
      fail_input("the checkpoint '", path, "' holds ", restored.n_sites(), " sites and ",
                 restored.bodies().size(), " adipocytes, this System ", sim.system.n_sites(),
                 " sites and ", sim.system.bodies().size(),
                 " adipocytes (load into a System built with the same sizes)");
    sim.system = std::move(restored);
    if (seed) sim.system.set_seed(std::uint64_t(*seed));
    for (const auto& term : sim.forces.terms()) term->invalidate_caches();
    if (p.tethers) {
      p.tethers->force->clear();
      read_tethers(r, sim.system, *p.tethers->force);
    }
    if (p.correlator) read_correlator(r, *p.correlator);
    sim.changed();
    if (p.dyn) {
      read_dynamics(r, p.dyn->dynamics);
      prepare_dynamics(*p.dyn, p.sim, "load_checkpoint");  // links the pressure wall
      p.dyn->dynamics.mark_prepared();
      p.dyn->last = p.sim;
      p.dyn->last_revision = sim.revision;
    }
    extra = r.get_string("extra");
  });
  return push_results(L, 1, [&extra](lua_State* S) noexcept {
    lua_pushlstring(S, extra.data(), extra.size());
    return 1;
  });
}

// invasim.checkpoint_run(path) -> run id, run parameters (strings; nil where not stored).
int l_checkpoint_run(lua_State* L) {
  const std::string path = arg_string(L, 1);
  std::optional<std::string> id, parameters;
  engine_call("checkpoint_run", [&] {
    const CheckpointReader r = CheckpointReader::read(path);
    if (r.has("run.id")) id = r.get_string("run.id");
    if (r.has("run.parameters")) parameters = r.get_string("run.parameters");
  });
  for (const auto& value : {id, parameters}) {
    if (value)
      lua_pushlstring(L, value->data(), value->size());
    else
      lua_pushnil(L);
  }
  return 2;
}

int l_interrupted(lua_State* L) {
  const int signal = stop_requested();
  return push_results(L, 1, [signal](lua_State* S) noexcept {
    if (signal)
      lua_pushstring(S, stop_signal_name(signal));
    else
      lua_pushnil(S);
    return 1;
  });
}

}  // namespace

void open_checkpoint(lua_State* L) {
  install_stop_handlers();
  lua_pushcfunction(L, &lua_wrap<&l_save>);
  lua_setfield(L, -2, "save_checkpoint");
  lua_pushcfunction(L, &lua_wrap<&l_load>);
  lua_setfield(L, -2, "load_checkpoint");
  lua_pushcfunction(L, &lua_wrap<&l_load>);
  lua_setfield(L, -2, "load");  // invasim.load(path, {...}): the same, shorter
  lua_pushcfunction(L, &lua_wrap<&l_checkpoint_run>);
  lua_setfield(L, -2, "checkpoint_run");
  lua_pushcfunction(L, &lua_wrap<&l_interrupted>);
  lua_setfield(L, -2, "interrupted");
}

}  // namespace invasim::lua
