// invasim.Dynamics{dt = 0.05}: time stepping of a System by a list of methods (Damped,
// Langevin, Active), with an optional pressure-controlled left wall:
//   dyn:add(method); dyn:pressure_wall{P =, mass = 1, gamma = 0.2, kT = 0, walls = w}
//   dyn:run(sys, nsteps [, {every = N, callback = function(step, time) end, progress = p}])
// run steps the engine through a run/ Simulation and returns to Lua only between chunks.
#include <lua.hpp>

#include <algorithm>
#include <limits>

#include "core/names.hpp"
#include "lua/adapters.hpp"
#include "lua/engine_fields.hpp"
#include "lua/engine_types.hpp"
#include "lua/function_operation.hpp"
#include "lua/module.hpp"

namespace invasim::lua {

std::string LuaType<DynamicsHandle>::describe(const DynamicsHandle& d) {
  std::string text = cat("Dynamics(dt=", d.dynamics.dt(), ", methods:");
  for (const auto& m : d.methods) text += " " + m->kind;
  if (d.methods.empty()) text += " none";
  if (auto w = d.dynamics.pressure_wall()) text += cat(", pressure wall P=", w->pressure);
  return text + ")";
}

namespace {

// Refuses a change of d's methods or pressure wall during its run: run_steps checked them (the
// methods' System, the piston's Walls) when the run began.
void require_not_running(const DynamicsHandle& d, const char* what) {
  if (d.running)
    fail_input(what,
               ": the Dynamics is running (this call comes from a callback of its run); change "
               "its methods and pressure wall before the run, or after the run returns");
}

// The keys of invasim.Dynamics{} (the engine's Dynamics takes dt without a default: this is
// its one default).
struct DynamicsKeys {
  double dt = 0.05;
};

const FieldTable<DynamicsKeys>& dynamics_fields() {
  static const FieldTable<DynamicsKeys> table(
      "Dynamics", {number<DynamicsKeys>("dt", &DynamicsKeys::dt, Range::positive(), "tau",
                                        "time step of the integrator")});
  return table;
}

// The keys of dyn:pressure_wall{} besides `walls`; defaults: PressureWall's.
const FieldTable<PressureWall>& pressure_wall_fields() {
  using P = PressureWall;
  static const FieldTable<P> table(
      "pressure_wall",
      {
          required(number_or_ramp<P>("P", &P::pressure, &P::pressure_ramp, Range::non_negative(),
                                     "eps_c/sigma^3", "pressure on the left wall")),
          number<P>("mass", &P::mass, Range::positive(), "m", "mass of the piston"),
          number<P>("gamma", &P::gamma, Range::non_negative(), "sqrt(m eps_c)/sigma",
                    "damping coefficient of the piston"),
          number<P>("kT", &P::kT, Range::non_negative(), "eps_c",
                    "temperature of the piston's bath (0: no noise)"),
      });
  return table;
}

int l_new(lua_State* L) {
  Kwargs kw(L, 1, "Dynamics");
  const double dt = dynamics_fields().make(kw).dt;
  push(L, engine_call("Dynamics", [&] { return std::make_shared<DynamicsHandle>(dt); }));
  return 1;
}

// dyn:add(method): a Damped, Langevin or Active method; returns it.
int l_add(lua_State* L) {
  DynamicsHandle& d = check<DynamicsHandle>(L, 1);
  const auto& method = check_shared<MethodHandle>(L, 2);
  require_not_running(d, "add");
  for (const auto& m : d.methods)
    if (m == method) fail_input("add: this ", method->kind, " method is already in the Dynamics");
  d.methods.push_back(method);
  d.dynamics.add(method->method);
  d.dynamics.invalidate();
  lua_settop(L, 2);
  return 1;
}

// dyn:pressure_wall{P =, mass = 1, gamma = 0.2, kT = 0, walls = w}: the left wall becomes a
// piston under pressure P, damped by gamma, with FDT noise at temperature kT (0: none). walls
// defaults to the System's only Walls force (found at run time).
int l_pressure_wall(lua_State* L) {
  DynamicsHandle& d = check<DynamicsHandle>(L, 1);
  require_not_running(d, "pressure_wall");
  Kwargs kw(L, 2, "pressure_wall");
  auto wall = std::make_shared<PressureWall>(pressure_wall_fields().read(kw));
  std::shared_ptr<Walls> walls = kw_object<Walls>(kw, "walls", false, "a Walls force");
  kw.finish();
  d.walls = walls;
  d.dynamics.set_pressure_wall(std::move(wall));
  d.dynamics.invalidate();
  return 0;
}

// dyn:wall_state() -> {P =, velocity =, force =, kT =} or nil without a pressure wall.
int l_wall_state(lua_State* L) {
  const auto wall = check<DynamicsHandle>(L, 1).dynamics.pressure_wall();
  if (!wall) {
    lua_pushnil(L);
    return 1;
  }
  return push_record(L, {{"P", wall->pressure},
                         {"velocity", wall->velocity},
                         {"force", wall->force},
                         {"kT", wall->kT}});
}

// The Dynamics' pressure wall, or an error naming the method `what` that needs one.
std::shared_ptr<PressureWall> require_pressure_wall(DynamicsHandle& d, const char* what) {
  auto wall = d.dynamics.pressure_wall();
  if (!wall)
    fail_input(what,
               ": this Dynamics has no pressure wall; add one with dyn:pressure_wall{P = "
               "...}");
  return wall;
}

// dyn:set_pressure(P): a number or a ramp; the piston keeps its velocity.
int l_set_pressure(lua_State* L) {
  DynamicsHandle& d = check<DynamicsHandle>(L, 1);
  const auto wall = require_pressure_wall(d, "set_pressure");
  lua_settop(L, 2);
  lua_pushvalue(L, 2);
  protected_call(L, 1, 1, [](lua_State* S) noexcept {  // {P = argument 2}
    lua_createtable(S, 0, 1);
    lua_pushvalue(S, 1);
    lua_setfield(S, -2, "P");
    return 1;
  });
  Kwargs kw(L, 3, "set_pressure");
  const NumberOrRamp P = kw_number_or_ramp(kw, "P", Range::non_negative());
  kw.finish();
  wall->pressure = P.value;
  wall->pressure_ramp = P.ramp;
  return 0;
}

int l_methods(lua_State* L) {
  const DynamicsHandle& d = check<DynamicsHandle>(L, 1);
  push_list(L, d.methods.size(), [&](std::size_t k) { push(L, d.methods[k]); });
  return 1;
}

// dyn:run(sys, nsteps [, {every = N, callback = f, progress = p}]) -> steps done.
// callback(step, time) runs after each step of the System that is a multiple of `every`
// (required with a callback); returning false stops the run there. progress:update is called
// after each chunk (every `every` steps, else every 100). The run itself is a
// run/simulation.hpp Simulation with the callback as its one operation.
int l_run(lua_State* L) {
  const std::shared_ptr<DynamicsHandle> d = check_shared<DynamicsHandle>(L, 1);
  const std::shared_ptr<SystemHandle> sim = check_shared<SystemHandle>(L, 2);
  const long long n = arg_integer(L, 3, 0, std::numeric_limits<long long>::max());  // steps
  std::optional<long long> every;
  int callback = 0;
  std::shared_ptr<Progress> progress;
  if (!lua_isnoneornil(L, 4)) {
    Kwargs kw(L, 4, "run");
    every = kw.maybe_integer<long long>("every", Range::at_least(1));
    callback = kw_function(kw, "callback");
    progress = kw_object<Progress>(kw, "progress");
    kw.finish();
    if (callback && !every) fail_input("run: a callback needs key 'every' (call it every N steps)");
  }
  invasim::Simulation run = make_simulation(sim, d);
  if (every) run.set_max_chunk(static_cast<std::uint64_t>(*every));
  if (callback) {
    auto op = std::make_shared<LuaFunctionOperation>(L, callback, sim, d, "callback");
    op->set_thread(L);  // the caller's thread (a coroutine's, when run inside one)
    run.add(op, Trigger::every(static_cast<std::uint64_t>(*every)));
  }
  const RunResult result = engine_call("run", [&] { return run_steps(run, sim, *d, n, progress); });
  lua_pushinteger(L, static_cast<lua_Integer>(result.steps));  // the caller checks
  return 1;                                                    // invasim.interrupted()
}

}  // namespace

void open_dynamics(lua_State* L) {
  define_type<DynamicsHandle>(
      L,
      {INVASIM_LUA_FN(add), INVASIM_LUA_FN(pressure_wall), INVASIM_LUA_FN(wall_state),
       getter<DynamicsHandle, [](const DynamicsHandle& d) { return d.dynamics.dt(); }>("dt"),
       // steps run in the parallel team by more than one thread (Dynamics::parallel_steps)
       getter<DynamicsHandle, [](const DynamicsHandle& d) { return d.dynamics.parallel_steps(); }>(
           "parallel_steps"),
       method<"set_dt", [](DynamicsHandle& d, double dt) { d.dynamics.set_dt(dt); }>(),
       // steps between two choices of the engine order (Dynamics::sort_every)
       method<"set_sort_every",
              [](DynamicsHandle& d, std::uint64_t n) { d.dynamics.set_sort_every(n); }>(),
       INVASIM_LUA_FN(set_pressure),
       // the temperature of the piston's bath (>= 0; 0: no noise)
       method<"set_wall_kT",
              [](DynamicsHandle& d, double kT) {
                const auto wall = require_pressure_wall(d, "set_wall_kT");
                if (!(kT >= 0.0)) fail_input("kT = ", kT, " must be >= 0");
                if (kT == wall->kT) return;  // unchanged: the prepared forces stay (set_dt)
                wall->kT = kT;
                d.dynamics.invalidate();
              }>(),
       INVASIM_LUA_FN(methods), INVASIM_LUA_FN(run)});
  set_constructor(L, "Dynamics", &lua_wrap<&l_new>, dynamics_fields().infos());
  static const std::vector<Declaration> pressure_wall_keys =
      with_options(pressure_wall_fields().infos(),
                   {option_key("walls", "Walls", "the Walls force whose left wall is the piston")});
  set_method_keys(L, "Dynamics", "pressure_wall", pressure_wall_keys);
}

}  // namespace invasim::lua
