#pragma once
// A bound object's C++ object is freed by its metatable's __gc (detail::gc, which destroys by
// the userdata's own type tag). debug.setmetatable can give the userdata a metatable without
// that finaliser (nil, a plain table, the FILE* metatable); Lua would then free the userdata's
// memory without ever destroying the shared_ptr inside it, and the C++ object would leak.
// guard_bound_finalizers() replaces debug.setmetatable with a version that refuses exactly
// that: a bound object may be given another invasim type's metatable (every invasim __gc
// dispatches on the tag), never one without invasim's __gc. Other values are passed through.
struct lua_State;

namespace invasim::lua {

// Installs the guarded debug.setmetatable (after luaL_openlibs).
void guard_bound_finalizers(lua_State* L);

}  // namespace invasim::lua
