#pragma once
// The `invasim` module table. open_invasim is the package.preload loader; it calls one
// open_<part> per binding file, each adding its functions and types to the table on top of
// the stack. A new binding file adds its open_<part> here and in module.cpp.
struct lua_State;

namespace invasim::lua {

// Loader for require("invasim"): pushes the module table (wrap with lua_wrap).
int open_invasim(lua_State* L);

void open_params(lua_State* L);    // invasim.params{...}        (bind_params.cpp)
void open_progress(lua_State* L);  // invasim.Progress{...}      (bind_progress.cpp)

}  // namespace invasim::lua
