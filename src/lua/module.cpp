#include "lua/module.hpp"

#include <omp.h>
#include <lua.hpp>

#include "invasim_version.hpp"
#include "lua/context.hpp"

namespace invasim::lua {

namespace {

// invasim.threads(): the number of OpenMP threads a parallel loop will use.
int l_threads(lua_State* L) {
  lua_pushinteger(L, omp_get_max_threads());
  return 1;
}

}  // namespace

int open_invasim(lua_State* L) {
  const ScriptContext& context = script_context(L);
  lua_newtable(L);
  lua_pushstring(L, kInvasimVersion);
  lua_setfield(L, -2, "version");
  lua_pushstring(L, context.options.out_dir.c_str());
  lua_setfield(L, -2, "out_dir");
  lua_pushstring(L, context.options.script_path.c_str());
  lua_setfield(L, -2, "script");
  lua_pushcfunction(L, &l_threads);
  lua_setfield(L, -2, "threads");
  open_params(L);
  open_progress(L);
  open_system(L);
  open_group(L);
  open_contacts(L);
  open_walls(L);
  open_shape(L);
  open_tethers(L);
  open_method(L);
  open_dynamics(L);
  open_fire(L);
  open_compression(L);
  return 1;
}

}  // namespace invasim::lua
