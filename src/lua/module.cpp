#include "lua/module.hpp"

#include <omp.h>
#include <lua.hpp>

#include <chrono>

#include "core/fnv1a.hpp"
#include "invasim_version.hpp"
#include "lua/adapters.hpp"
#include "lua/binding.hpp"
#include "lua/context.hpp"
#include "lua/lua_state.hpp"

namespace invasim::lua {

// open_<part> of every bind_<part>.cpp.
#define INVASIM_LUA_PART(part) void open_##part(lua_State* L);
#include "lua_bindings.inc"
#undef INVASIM_LUA_PART

namespace {

// invasim.at_error(f): f(message) is called when the script ends with an error (a stop by a
// signal included), after the stack has unwound and before invasim reports it: lib.log writes
// the message to the run's log.txt. Functions run in the order registered; an error of one is
// a warning on stderr (LuaState::run_error_functions).
int l_at_error(lua_State* L) {
  if (lua_type(L, 1) != LUA_TFUNCTION) throw InputError(bad_argument(L, 1, "function"));
  lua_pushvalue(L, 1);
  protected_call(L, 1, 0, [](lua_State* S) noexcept {
    luaL_getsubtable(S, LUA_REGISTRYINDEX, kAtErrorRegistryKey);
    lua_pushvalue(S, 1);
    lua_rawseti(S, -2, static_cast<lua_Integer>(lua_rawlen(S, -2)) + 1);
    return 0;
  });
  return 0;
}

}  // namespace

int open_invasim(lua_State* L) {
  {
    const RunOptions& o = script_context(L).options;
    Record fields{{"version", kInvasimVersion},
                  {"git_revision", kInvasimGitRevision[0] ? kInvasimGitRevision : "unknown"},
                  {"out_dir", o.out_dir},
                  {"overwrite", o.overwrite},  // --overwrite: replace the run in out_dir
                  {"script", o.script_path}};
    if (!o.from_dir.empty()) fields.push_back({"from", o.from_dir});  // the tissue's run
    if (o.resume) fields.push_back({"resume", o.out_dir});  // the run directory to continue
    if (!o.continue_command.empty()) fields.push_back({"continue_command", o.continue_command});
    push_record(L, fields);
  }  // no C++ object is left in this frame: the bindings below may raise Lua errors
  add_functions(L,
                {// invasim.threads(): the number of OpenMP threads a parallel loop will use.
                 method<"threads", [] { return omp_get_max_threads(); }>(),
                 // invasim.clock(): wall-clock seconds from a steady clock (for timing stages;
                 // os.clock is CPU time summed over threads).
                 method<"clock",
                        [] {
                          const auto now = std::chrono::steady_clock::now().time_since_epoch();
                          return std::chrono::duration<double>(now).count();
                        }>(),
                 // invasim.hash(text): FNV-1a 64 of the bytes, as 16 hex digits (a run's identity).
                 method<"hash", [](std::string text) { return fnv1a64_hex(text); }>(),
                 // invasim.stop(): ends the script here, without an error (exit status 0).
                 method<"stop", []() -> void { throw StopScript(); }>(), INVASIM_LUA_FN(at_error)});
#define INVASIM_LUA_PART(part) open_##part(L);
#include "lua_bindings.inc"
#undef INVASIM_LUA_PART
  return 1;
}

}  // namespace invasim::lua
