#include "lua/error_object.hpp"

#include <lua.hpp>

#include "lua/binding.hpp"

namespace invasim::lua {

int describe_error_object(lua_State* L) {
  if (lua_type(L, 1) == LUA_TSTRING || is_stop_sentinel(L, 1)) {
    lua_settop(L, 1);
    return 1;
  }
  lua_settop(L, 1);
  push_where(L);  // 2: "file:line: " of the caller of error(), or ""
  lua_pushfstring(L, "error object is a %s value", luaL_typename(L, 1));  // 3
  const int type = lua_type(L, 1);
  if (luaL_getmetafield(L, 1, "__tostring") != LUA_TNIL) {  // 4: __tostring
    lua_pushvalue(L, 1);
    if (lua_pcall(L, 1, 1, 0) == LUA_OK && lua_type(L, -1) == LUA_TSTRING) {
      lua_pushliteral(L, ": ");
      lua_insert(L, -2);
    } else {
      const char* why = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : "no string";
      lua_pushfstring(L, " (its __tostring failed: %s)", why);
      lua_remove(L, -2);
    }
  } else if (type == LUA_TNUMBER || type == LUA_TBOOLEAN) {
    lua_pushliteral(L, ": ");
    luaL_tolstring(L, 1, nullptr);
  } else {
    lua_pushliteral(L, " (no message)");
  }
  lua_concat(L, lua_gettop(L) - 1);
  return 1;
}

}  // namespace invasim::lua
