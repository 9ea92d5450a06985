#pragma once
// The Lua side of the run layer (run/simulation.hpp): the engine Simulation of a System
// userdata and a Dynamics, and the operation that calls a Lua function (an observer written in
// Lua; the engine knows no Lua).
#include <lua.hpp>

#include <memory>
#include <string>

#include "io/snapshot_writer.hpp"
#include "lua/engine_types.hpp"
#include "run/operation.hpp"
#include "run/simulation.hpp"

namespace invasim::lua {

// An engine Simulation stepping `system`'s System and ForceField with `d`'s Dynamics; its
// pointers share ownership of the two Lua objects (aliasing shared_ptrs).
invasim::Simulation engine_simulation(const std::shared_ptr<SystemHandle>& system,
                                      const std::shared_ptr<DynamicsHandle>& d);

// Runs n steps of `run` (made by engine_simulation from `system` and `d`), the one path of
// dyn:run and sim:run: `progress` (may be null) hears of every chunk; the Dynamics is prepared
// first, and afterwards the System is marked changed and the Dynamics as having run on it.
RunResult run_steps(invasim::Simulation& run, const std::shared_ptr<SystemHandle>& system,
                    DynamicsHandle& d, long long n, const std::shared_ptr<Progress>& progress);

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
  lua_State* main_;
  lua_State* current_;
  int ref_ = LUA_NOREF;
  std::shared_ptr<SystemHandle> system_;
  std::shared_ptr<DynamicsHandle> dynamics_;
  std::string name_;
};

}  // namespace invasim::lua
