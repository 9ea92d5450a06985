#include "lua/finalizer_guard.hpp"

#include <lua.hpp>

#include "lua/binding.hpp"

namespace invasim::lua {

namespace {

// Whether the value at `index` is a table whose raw __gc is invasim's finaliser. Raw, as Lua
// reads __gc when it collects: a __gc reached only through the table's own __index is never
// called.
bool has_invasim_finalizer(lua_State* L, int index) {
  if (lua_type(L, index) != LUA_TTABLE) return false;
  lua_pushliteral(L, "__gc");
  lua_rawget(L, index);
  const bool ours = lua_tocfunction(L, -1) == &detail::gc;
  lua_pop(L, 1);
  return ours;
}

// debug.setmetatable(value, table|nil), refusing to strip a bound object of invasim's __gc.
// Plain C-style code (luaL_error unwinds with longjmp): no C++ object is alive here.
int guarded_setmetatable(lua_State* L) {
  const TypeTag* tag = detail::tag_at(L, 1);
  if (tag != nullptr && !has_invasim_finalizer(L, 2))
    return luaL_error(L,
                      "debug.setmetatable: a bound %s must keep an invasim metatable (this one "
                      "has no invasim __gc, so its C++ object would never be freed)",
                      tag->name);
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
  return lua_gettop(L);
}

}  // namespace

void guard_bound_finalizers(lua_State* L) {
  lua_getglobal(L, "debug");
  if (lua_type(L, -1) == LUA_TTABLE) {
    lua_getfield(L, -1, "setmetatable");
    lua_pushcclosure(L, &guarded_setmetatable, 1);
    lua_setfield(L, -2, "setmetatable");
  }
  lua_pop(L, 1);
}

}  // namespace invasim::lua
