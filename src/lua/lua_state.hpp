#pragma once
// LuaState: owns one lua_State with the standard libraries, the `invasim` module available
// through require("invasim") (package.preload), and the ScriptContext (command-line options in,
// declared parameters out). Scripts run under a traceback message handler; a Lua error comes
// back as a ScriptError whose what() is "file:line: message" (also for error objects that are
// not strings: lua/error_object.hpp). os.exit raises an error instead of ending the process,
// and the stop hook (lua/stop_hook.hpp) lets SIGINT/SIGTERM end a script stuck in Lua code.
#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>

#include "core/errors.hpp"

#include "lua/context.hpp"

struct lua_State;

namespace invasim::lua {

// A Lua error from a running script: what() is the message ("proto.lua:12: ..."), with its
// control characters escaped as fail_input's are (core/errors.hpp: a NUL would end it);
// traceback() the Lua stack at the error (empty for syntax errors).
class ScriptError : public std::runtime_error {
 public:
  ScriptError(const std::string& message, std::string traceback)
      : std::runtime_error(printable_message(message)), traceback_(std::move(traceback)) {}
  const std::string& traceback() const { return traceback_; }

 private:
  std::string traceback_;
};

// The registry key of the list of functions invasim.at_error registers.
inline constexpr const char* kAtErrorRegistryKey = "invasim.at_error";

class LuaState {
 public:
  enum class Outcome { kCompleted, kStopped };  // kStopped: a binding raised StopScript

  explicit LuaState(RunOptions options = {});
  ~LuaState();
  LuaState(const LuaState&) = delete;
  LuaState& operator=(const LuaState&) = delete;

  lua_State* get() const { return L_; }
  ScriptContext& context() { return *context_; }

  // Bytes the Lua allocator holds now, and a cap on them (0: none, the default): an allocation
  // that would exceed it fails, which Lua raises as a memory error ("not enough memory"). For
  // tests of the bindings' behaviour when memory runs out midway.
  std::size_t memory_used() const;
  void set_memory_limit(std::size_t bytes);

  // Runs a script file; its directory is prepended to package.path so that it can require
  // its neighbours. A missing file is an InputError, a Lua error a ScriptError.
  Outcome run_file(const std::string& path);
  // Runs a chunk of code (tests, --eval-like uses); `chunkname` as in lua_load ("=name").
  Outcome run_string(const std::string& code, const std::string& chunkname = "=(string)");

 private:
  Outcome call_loaded(int load_status);
  // Calls the functions invasim.at_error registered, in order, with the message of the error
  // that ends the script (protected; their own errors are warnings on stderr).
  void run_error_functions(const std::string& message);

  // The allocator's bookkeeping (lua_Alloc user data).
  struct Memory {
    std::size_t used = 0;
    std::size_t limit = 0;
  };
  static void* allocate(void* ud, void* block, std::size_t old_size, std::size_t new_size);

  std::unique_ptr<ScriptContext> context_;
  std::unique_ptr<Memory> memory_;
  lua_State* L_ = nullptr;
};

}  // namespace invasim::lua
