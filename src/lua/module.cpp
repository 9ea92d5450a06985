#include "lua/module.hpp"

#include <omp.h>
#include <lua.hpp>

#include <chrono>

#include "core/fnv1a.hpp"
#include "invasim_version.hpp"
#include "lua/binding.hpp"
#include "lua/context.hpp"

namespace invasim::lua {

// open_<part> of every bind_<part>.cpp.
#define INVASIM_LUA_PART(part) void open_##part(lua_State* L);
#include "lua_bindings.inc"
#undef INVASIM_LUA_PART

namespace {

// invasim.threads(): the number of OpenMP threads a parallel loop will use.
int l_threads(lua_State* L) {
  lua_pushinteger(L, omp_get_max_threads());
  return 1;
}

// invasim.clock(): wall-clock seconds from a steady clock (for timing stages; os.clock is
// CPU time summed over threads).
int l_clock(lua_State* L) {
  const auto now = std::chrono::steady_clock::now().time_since_epoch();
  lua_pushnumber(L, std::chrono::duration<double>(now).count());
  return 1;
}

// invasim.hash(text): FNV-1a 64 of the bytes, as 16 hex digits (a run's identity).
int l_hash(lua_State* L) {
  std::size_t size = 0;
  const char* text = luaL_checklstring(L, 1, &size);
  const std::string hex = fnv1a64_hex(std::string_view(text, size));
  lua_pushlstring(L, hex.data(), hex.size());
  return 1;
}

}  // namespace

int open_invasim(lua_State* L) {
  const ScriptContext& context = script_context(L);
  lua_newtable(L);
  lua_pushstring(L, kInvasimVersion);
  lua_setfield(L, -2, "version");
  lua_pushstring(L, kInvasimGitRevision[0] ? kInvasimGitRevision : "unknown");
  lua_setfield(L, -2, "git_revision");
  lua_pushstring(L, context.options.out_dir.c_str());
  lua_setfield(L, -2, "out_dir");
  if (!context.options.from_dir.empty()) {  // invasim.from: a run whose tissue to start from
    lua_pushstring(L, context.options.from_dir.c_str());
    lua_setfield(L, -2, "from");
  }
  if (context.options.resume) {  // invasim.resume: the run directory to continue, else nil
    lua_pushstring(L, context.options.out_dir.c_str());
    lua_setfield(L, -2, "resume");
  }
  if (!context.options.continue_command.empty()) {
    lua_pushstring(L, context.options.continue_command.c_str());
    lua_setfield(L, -2, "continue_command");
  }
  lua_pushboolean(L, context.options.overwrite);  // --overwrite: replace the run in out_dir
  lua_setfield(L, -2, "overwrite");
  lua_pushstring(L, context.options.script_path.c_str());
  lua_setfield(L, -2, "script");
  add_functions(L, {
                       {"threads", &l_threads},
                       {"clock", &l_clock},
                       {"hash", &l_hash},
                   });
#define INVASIM_LUA_PART(part) open_##part(L);
#include "lua_bindings.inc"
#undef INVASIM_LUA_PART
  return 1;
}

}  // namespace invasim::lua
