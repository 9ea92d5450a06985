#pragma once
// The `invasim` module table. open_invasim is the package.preload loader; it calls the
// open_<part>(lua_State*) of every binding file src/lua/bind_<part>.cpp (listed by the build in
// generated/lua_bindings.inc), each adding its functions and types to the table on top of the
// stack.
struct lua_State;

namespace invasim::lua {

// Loader for require("invasim"): pushes the module table (wrap with lua_wrap).
int open_invasim(lua_State* L);

}  // namespace invasim::lua
