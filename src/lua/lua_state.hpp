#pragma once
// LuaState: owns one lua_State with the standard libraries, the `invasim` module available
// through require("invasim") (package.preload), and the ScriptContext (command-line options in,
// declared parameters out). Scripts run under a traceback message handler; a Lua error comes
// back as a ScriptError whose what() is "file:line: message".
#include <memory>
#include <stdexcept>
#include <string>

#include "lua/context.hpp"

struct lua_State;

namespace invasim::lua {

// A Lua error from a running script: what() is the message ("proto.lua:12: ..."), traceback()
// the Lua stack at the error (empty for syntax errors).
class ScriptError : public std::runtime_error {
 public:
  ScriptError(const std::string& message, std::string traceback)
      : std::runtime_error(message), traceback_(std::move(traceback)) {}
  const std::string& traceback() const { return traceback_; }

 private:
  std::string traceback_;
};

class LuaState {
 public:
  enum class Outcome { kCompleted, kStopped };  // kStopped: a binding raised StopScript

  explicit LuaState(RunOptions options = {});
  ~LuaState();
  LuaState(const LuaState&) = delete;
  LuaState& operator=(const LuaState&) = delete;

  lua_State* get() const { return L_; }
  ScriptContext& context() { return *context_; }

  // Runs a script file; its directory is prepended to package.path so that it can require
  // its neighbours. A missing file is an InputError, a Lua error a ScriptError.
  Outcome run_file(const std::string& path);
  // Runs a chunk of code (tests, --eval-like uses); `chunkname` as in lua_load ("=name").
  Outcome run_string(const std::string& code, const std::string& chunkname = "=(string)");

 private:
  Outcome call_loaded(int load_status);

  std::unique_ptr<ScriptContext> context_;
  lua_State* L_ = nullptr;
};

}  // namespace invasim::lua
