#include "lua/lua_state.hpp"

#include <lua.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <new>
#include <string_view>

#include "core/errors.hpp"
#include "io/regular_file.hpp"
#include "lua/binding.hpp"
#include "lua/error_object.hpp"
#include "lua/finalizer_guard.hpp"
#include "lua/module.hpp"
#include "lua/stop_hook.hpp"
#include "lua/text_chunks.hpp"

namespace invasim::lua {

namespace {

constexpr const char* kContextKey = "invasim.context";

// Message handler of every script run: leaves the stop sentinel alone, otherwise returns
// {message, traceback}: a non-string error object described with the place it was raised,
// and for an error from a callback the traceback recorded where it was raised (both
// lua/error_object.hpp). Plain C-style code: nothing here owns a C++ object.
int message_handler(lua_State* L) {
  if (is_stop_sentinel(L, 1)) return 1;
  lua_settop(L, 1);
  lua_pushcfunction(L, &describe_error_object);
  lua_insert(L, 1);
  lua_call(L, 1, 1);
  lua_createtable(L, 2, 0);
  lua_pushvalue(L, 1);  // the message as a Lua string: a NUL inside does not end it
  lua_rawseti(L, -2, 1);
  // An error raised in a callback and re-raised by its binding: the stack where it began.
  if (!take_callback_traceback(L, 1)) luaL_traceback(L, L, nullptr, 1);
  lua_rawseti(L, -2, 2);
  return 1;
}

// The string (or number) at `index` whole, NULs included (a C string would end at the first).
std::string string_at(lua_State* L, int index) {
  std::size_t length = 0;
  const char* text = lua_tolstring(L, index, &length);
  return std::string(text, length);
}

// os.exit in a protocol: an error, not an end of the process that would leave the run's files
// (series.csv, log.txt, a checkpoint in progress) unfinished and report success.
int refuse_os_exit(lua_State* L) {
  return luaL_error(L,
                    "os.exit is not allowed in a protocol: it would end invasim without "
                    "finishing the run's files; use error(message) to stop with a failure, or "
                    "return to end the script normally");
}

// As lauxlib's panic function: an error outside any protected call ends the process.
int panic(lua_State* L) {
  const char* message = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : "error object";
  std::fprintf(stderr, "invasim: unprotected error in Lua: %s\n", message);
  std::fflush(stderr);
  return 0;  // Lua then aborts
}

}  // namespace

ScriptContext& script_context(lua_State* L) {
  lua_getfield(L, LUA_REGISTRYINDEX, kContextKey);
  auto* context = static_cast<ScriptContext*>(lua_touserdata(L, -1));
  lua_pop(L, 1);
  if (context == nullptr) throw std::logic_error("Lua state has no invasim context");
  return *context;
}

// lua_Alloc (the contract of lauxlib's l_alloc) that counts the bytes it holds and refuses to
// grow beyond the limit; freeing and shrinking always succeed.
void* LuaState::allocate(void* ud, void* block, std::size_t old_size, std::size_t new_size) {
  auto& memory = *static_cast<Memory*>(ud);
  const std::size_t held = block ? old_size : 0;
  if (new_size == 0) {
    std::free(block);
    memory.used -= held;
    return nullptr;
  }
  if (new_size > held && memory.limit != 0 && memory.used - held + new_size > memory.limit)
    return nullptr;
  void* result = std::realloc(block, new_size);
  if (result != nullptr) memory.used = memory.used - held + new_size;
  return result;
}

std::size_t LuaState::memory_used() const {
  return memory_->used;
}

void LuaState::set_memory_limit(std::size_t bytes) {
  memory_->limit = bytes;
}

LuaState::LuaState(RunOptions options)
    : context_(std::make_unique<ScriptContext>(ScriptContext{std::move(options), {}})),
      memory_(std::make_unique<Memory>()) {
  L_ = lua_newstate(&LuaState::allocate, memory_.get());
  if (L_ == nullptr) throw std::bad_alloc();
  lua_atpanic(L_, &panic);
  luaL_openlibs(L_);
  restrict_to_text_chunks(L_);
  guard_bound_finalizers(L_);
  lua_getglobal(L_, "os");
  lua_pushcfunction(L_, &refuse_os_exit);
  lua_setfield(L_, -2, "exit");
  lua_pop(L_, 1);
  install_stop_hook(L_);
  lua_pushlightuserdata(L_, context_.get());
  lua_setfield(L_, LUA_REGISTRYINDEX, kContextKey);
  luaL_getsubtable(L_, LUA_REGISTRYINDEX, LUA_PRELOAD_TABLE);
  lua_pushcfunction(L_, &lua_wrap<&open_invasim>);
  lua_setfield(L_, -2, "invasim");
  lua_pop(L_, 1);
}

LuaState::~LuaState() {
  if (L_ != nullptr) lua_close(L_);
}

LuaState::Outcome LuaState::call_loaded(int load_status) {
  if (load_status != LUA_OK) {  // syntax error: "file:line: ... near ..."
    std::string message = lua_tostring(L_, -1) ? lua_tostring(L_, -1) : "cannot load script";
    lua_settop(L_, 0);
    throw ScriptError(message, "");
  }
  lua_pushcfunction(L_, &message_handler);
  lua_insert(L_, -2);
  const int handler = lua_gettop(L_) - 1;
  const int status = lua_pcall(L_, 0, 0, handler);
  if (status == LUA_OK) {
    lua_settop(L_, 0);
    return Outcome::kCompleted;
  }
  if (is_stop_sentinel(L_, -1)) {
    lua_settop(L_, 0);
    return Outcome::kStopped;
  }
  std::string message = "error in the Lua error handler", traceback;
  if (lua_type(L_, -1) == LUA_TTABLE) {
    lua_rawgeti(L_, -1, 1);
    lua_rawgeti(L_, -2, 2);
    if (lua_isstring(L_, -2)) message = string_at(L_, -2);
    if (lua_isstring(L_, -1)) traceback = string_at(L_, -1);
  } else if (lua_isstring(L_, -1)) {
    message = string_at(L_, -1);  // e.g. out of memory before the handler ran
  }
  lua_settop(L_, 0);  // run_error_functions starts from an empty stack
  run_error_functions(message);
  throw ScriptError(message, traceback);
}

void LuaState::run_error_functions(const std::string& message) {
  try {
    protected_call(L_, 0, 2, [&message](lua_State* S) noexcept {
      lua_getfield(S, LUA_REGISTRYINDEX, kAtErrorRegistryKey);
      lua_pushlstring(S, message.data(), message.size());
      return 2;
    });
  } catch (const std::exception&) {  // out of memory: the message is reported all the same
    lua_settop(L_, 0);
    return;
  }
  const lua_Integer n = lua_istable(L_, 1) ? static_cast<lua_Integer>(lua_rawlen(L_, 1)) : 0;
  for (lua_Integer i = 1; i <= n; ++i) {
    lua_rawgeti(L_, 1, i);
    lua_pushvalue(L_, 2);
    // Its own error (a full disk) is reported as a warning, and the script's error stays the
    // one the run ends with; a stop (Ctrl-C while it ran) is not an error of the function.
    if (lua_pcall(L_, 1, 0, 0) != LUA_OK && !is_stop_sentinel(L_, -1)) {
      const std::string failure =
          lua_type(L_, -1) == LUA_TSTRING ? string_at(L_, -1) : "an error object that is no string";
      std::fprintf(stderr, "invasim: warning: an invasim.at_error function failed: %s\n",
                   printable_message(failure).c_str());
      std::fflush(stderr);
    }
    lua_settop(L_, 2);
  }
  lua_settop(L_, 0);
}

LuaState::Outcome LuaState::run_file(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code error;
  if (!fs::exists(path, error)) fail_input("cannot open protocol file '", path, "': no such file");
  if (fs::is_directory(path, error))
    fail_input("cannot open protocol file '", path, "': it is a directory");
  require_regular_file(path, "protocol file");  // a FIFO or device would block or never end
  // Let the script require modules next to it: <dir>/?.lua and <dir>/?/init.lua first.
  const std::string parent = fs::path(path).parent_path().string();
  const std::string dir = parent.empty() ? std::string(".") : parent;
  const std::string prepend =
      "local dir = ...; package.path = dir .. '/?.lua;' .. dir .. '/?/init.lua;' .. package.path";
  if (luaL_loadstring(L_, prepend.c_str()) != LUA_OK) throw std::logic_error("package.path");
  lua_pushstring(L_, dir.c_str());
  if (lua_pcall(L_, 1, 0, 0) != LUA_OK) {
    lua_settop(L_, 0);
    throw std::runtime_error("cannot set package.path");
  }
  // Text only: Lua does not verify precompiled chunks, and a corrupted one crashes.
  const int status = luaL_loadfilex(L_, path.c_str(), "t");
  if (status == LUA_ERRFILE) {
    const std::string message = lua_tostring(L_, -1);
    lua_settop(L_, 0);
    fail_input(message);
  }
  if (status == LUA_ERRSYNTAX &&
      std::string_view(lua_tostring(L_, -1)).find("binary chunk") != std::string_view::npos) {
    const std::string message = lua_tostring(L_, -1);
    lua_settop(L_, 0);
    fail_input("cannot load protocol file '", path, "': ", message,
               ": invasim runs Lua source files only (precompiled chunks are refused)");
  }
  return call_loaded(status);
}

LuaState::Outcome LuaState::run_string(const std::string& code, const std::string& chunkname) {
  return call_loaded(luaL_loadbufferx(L_, code.data(), code.size(), chunkname.c_str(), "t"));
}

}  // namespace invasim::lua
