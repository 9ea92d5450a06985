#include "lua/run_glue.hpp"

#include "core/progress.hpp"

namespace invasim::lua {

invasim::Simulation engine_simulation(const std::shared_ptr<SystemHandle>& system,
                                      const std::shared_ptr<DynamicsHandle>& d) {
  return invasim::Simulation(std::shared_ptr<System>(system, &system->system),
                             std::shared_ptr<ForceField>(system, &system->forces),
                             std::shared_ptr<Dynamics>(d, &d->dynamics));
}

RunResult run_steps(invasim::Simulation& run, const std::shared_ptr<SystemHandle>& system,
                    DynamicsHandle& d, long long n, const std::shared_ptr<Progress>& progress) {
  if (progress)
    run.set_progress([progress](std::uint64_t done, double time) {
      progress->update(static_cast<long long>(done), time);
    });
  prepare_dynamics(d, system, "run");
  RunResult result;
  try {
    result = engine_call("run", [&] { return run.run(static_cast<std::uint64_t>(n)); });
  } catch (...) {
    run.set_progress({});
    throw;
  }
  run.set_progress({});
  system->changed();
  d.record.ran_on(system);
  return result;
}

LuaFunctionOperation::LuaFunctionOperation(lua_State* L, int index,
                                           std::shared_ptr<SystemHandle> system,
                                           std::shared_ptr<DynamicsHandle> d, std::string name)
    : system_(std::move(system)), dynamics_(std::move(d)), name_(std::move(name)) {
  index = lua_absindex(L, index);
  lua_rawgeti(L, LUA_REGISTRYINDEX, LUA_RIDX_MAINTHREAD);
  main_ = lua_tothread(L, -1);
  lua_pop(L, 1);
  current_ = main_;
  lua_pushvalue(L, index);
  protected_call(L, 1, 1, [](lua_State* S) noexcept {
    lua_pushinteger(S, luaL_ref(S, LUA_REGISTRYINDEX));
    return 1;
  });
  ref_ = static_cast<int>(lua_tointeger(L, -1));
  lua_pop(L, 1);
}

LuaFunctionOperation::~LuaFunctionOperation() {
  luaL_unref(main_, LUA_REGISTRYINDEX, ref_);  // writes existing registry slots only
}

void LuaFunctionOperation::apply(invasim::Simulation& sim) {
  lua_State* L = current_;
  if (!lua_checkstack(L, 4)) throw LuaApiError("Lua stack overflow");
  const std::uint64_t before = system_->revision;
  lua_rawgeti(L, LUA_REGISTRYINDEX, ref_);
  lua_pushinteger(L, static_cast<lua_Integer>(sim.system().step));
  lua_pushnumber(L, sim.system().time);
  call_lua(L, 2, 1);
  const bool stop = lua_type(L, -1) == LUA_TBOOLEAN && !lua_toboolean(L, -1);
  lua_pop(L, 1);
  if (system_->revision != before) {  // the function changed the System or its forces
    prepare_dynamics(*dynamics_, system_, name_);
    sim.state_changed();
  }
  dynamics_->record.ran_on(system_);
  if (stop) sim.request_stop();
}

std::string LuaFunctionOperation::call_for_string(invasim::Simulation& sim) {
  lua_State* L = current_;
  if (!lua_checkstack(L, 4)) throw LuaApiError("Lua stack overflow");
  lua_rawgeti(L, LUA_REGISTRYINDEX, ref_);
  lua_pushinteger(L, static_cast<lua_Integer>(sim.system().step));
  lua_pushnumber(L, sim.system().time);
  call_lua(L, 2, 1);
  if (lua_type(L, -1) != LUA_TSTRING) {
    const std::string got = luaL_typename(L, -1);
    lua_pop(L, 1);
    throw InputError(name_ + ": the function must return a string, got " + got);
  }
  std::size_t size = 0;
  const char* data = lua_tolstring(L, -1, &size);
  std::string text(data, size);
  lua_pop(L, 1);
  return text;
}

}  // namespace invasim::lua
