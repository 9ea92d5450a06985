#pragma once
// Lua chunks are loaded as text only. A precompiled (binary) chunk is not verified by Lua: a
// corrupted one crashes or hangs the process. LuaState loads protocols as text, and
// restrict_to_text_chunks() replaces what scripts can load with: `load`, `loadfile` and `dofile`
// force mode "t" (an explicit mode "b" is an error), and the Lua-file searcher of `require`
// (package.searchers[2]) loads modules as text.
struct lua_State;

namespace invasim::lua {

// Installs the text-only load, loadfile, dofile and require searcher (after luaL_openlibs).
void restrict_to_text_chunks(lua_State* L);

}  // namespace invasim::lua
