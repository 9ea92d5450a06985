#include "lua/function_operation.hpp"

namespace invasim::lua {

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

lua_State* LuaFunctionOperation::call(invasim::Simulation& sim) {
  lua_State* L = current_;
  if (!lua_checkstack(L, 4)) throw LuaApiError("Lua stack overflow");
  lua_rawgeti(L, LUA_REGISTRYINDEX, ref_);
  lua_pushinteger(L, static_cast<lua_Integer>(sim.system().step));
  lua_pushnumber(L, sim.system().time);
  call_lua(L, 2, 1);
  return L;
}

void LuaFunctionOperation::apply(invasim::Simulation& sim) {
  const std::uint64_t before = system_->revision;
  lua_State* L = call(sim);
  const int type = lua_type(L, -1);
  if (type != LUA_TNIL && type != LUA_TBOOLEAN) {  // 'stop', 0, ...: a mistaken stop, refused
    const std::string got = type_name_at(L, -1);
    lua_pop(L, 1);
    throw InputError(name_ + ": the function returned a " + got +
                     "; return false to stop the run, nothing or true to go on");
  }
  const bool stop = type == LUA_TBOOLEAN && !lua_toboolean(L, -1);
  lua_pop(L, 1);
  if (system_->revision != before) {  // the function changed the System or its forces
    prepare_dynamics(*dynamics_, system_, name_);
    sim.state_changed();
  }
  dynamics_->record.ran_on(system_);
  if (stop) sim.request_stop();
}

std::string LuaFunctionOperation::call_for_string(invasim::Simulation& sim) {
  lua_State* L = call(sim);
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
