#include "lua/module.hpp"

#include <omp.h>
#include <lua.hpp>

#include <chrono>

#include "core/fnv1a.hpp"
#include "invasim_version.hpp"
#include "lua/adapters.hpp"
#include "lua/binding.hpp"
#include "lua/context.hpp"

namespace invasim::lua {

// open_<part> of every bind_<part>.cpp.
#define INVASIM_LUA_PART(part) void open_##part(lua_State* L);
#include "lua_bindings.inc"
#undef INVASIM_LUA_PART

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
                 method<"stop", []() -> void { throw StopScript(); }>()});
#define INVASIM_LUA_PART(part) open_##part(L);
#include "lua_bindings.inc"
#undef INVASIM_LUA_PART
  return 1;
}

}  // namespace invasim::lua
