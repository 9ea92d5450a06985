#pragma once
// The run layer's operation that calls a Lua function (an observer written in Lua, a
// checkpoint's `extra` and `written`; the engine knows no Lua): run/operation.hpp.
#include <lua.hpp>

#include <memory>
#include <string>

#include "lua/engine_types.hpp"
#include "run/operation.hpp"
#include "run/simulation.hpp"

namespace invasim::lua {

// Calls a Lua function fn(step, time); a return value of false ends the run at this step.
// When the function changed the System (its revision moved), the Dynamics re-prepares before
// the next step. The function is kept in the registry until the operation is destroyed.
class LuaFunctionOperation : public Operation {
 public:
  // The function at stack index `index` of L.
  LuaFunctionOperation(lua_State* L, int index, std::shared_ptr<SystemHandle> system,
                       std::shared_ptr<DynamicsHandle> d, std::string name);
  ~LuaFunctionOperation() override;
  LuaFunctionOperation(const LuaFunctionOperation&) = delete;
  LuaFunctionOperation& operator=(const LuaFunctionOperation&) = delete;
  std::string name() const override { return name_; }
  void apply(invasim::Simulation& sim) override;
  // Calls the function and returns its result, which must be a string (else an InputError
  // naming the operation).
  std::string call_for_string(invasim::Simulation& sim);
  // The Lua thread to call the function on (the one running sim:run; default: main thread).
  void set_thread(lua_State* L) { current_ = L ? L : main_; }

 private:
  // Calls fn(step, time) on the current thread, leaving its one result on the stack top.
  lua_State* call(invasim::Simulation& sim);

  lua_State* main_;
  lua_State* current_;
  int ref_ = LUA_NOREF;
  std::shared_ptr<SystemHandle> system_;
  std::shared_ptr<DynamicsHandle> dynamics_;
  std::string name_;
};

}  // namespace invasim::lua
