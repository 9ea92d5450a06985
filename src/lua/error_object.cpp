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

namespace {
constexpr const char* kCallbackTracebackKey = "invasim.callback_traceback";  // {message, traceback}

// Whether the table at `index` records the message at stack index `message` (its entry 1),
// compared as Lua strings (a NUL inside does not end them). Leaves the stack as it was.
bool records_message(lua_State* L, int index, int message) {
  if (lua_type(L, index) != LUA_TTABLE) return false;
  lua_rawgeti(L, index, 1);
  const bool same = lua_type(L, -1) == LUA_TSTRING && lua_rawequal(L, -1, message);
  lua_pop(L, 1);
  return same;
}
}  // namespace

int callback_message_handler(lua_State* L) {
  describe_error_object(L);  // the description (or the stop sentinel) on top
  lua_copy(L, -1, 1);
  lua_settop(L, 1);
  if (lua_type(L, 1) != LUA_TSTRING) return 1;
  lua_getfield(L, LUA_REGISTRYINDEX, kCallbackTracebackKey);
  if (!records_message(L, -1, 1)) {
    lua_createtable(L, 2, 0);
    lua_pushvalue(L, 1);
    lua_rawseti(L, -2, 1);
    luaL_traceback(L, L, nullptr, 1);
    lua_rawseti(L, -2, 2);
    lua_setfield(L, LUA_REGISTRYINDEX, kCallbackTracebackKey);
  }
  lua_settop(L, 1);
  return 1;
}

bool take_callback_traceback(lua_State* L, int message) {
  message = lua_absindex(L, message);
  lua_getfield(L, LUA_REGISTRYINDEX, kCallbackTracebackKey);
  const bool recorded = records_message(L, -1, message);
  if (recorded) lua_rawgeti(L, -1, 2);
  lua_pushnil(L);
  lua_setfield(L, LUA_REGISTRYINDEX, kCallbackTracebackKey);
  if (recorded)
    lua_remove(L, -2);  // the record
  else
    lua_pop(L, 1);
  return recorded;
}

}  // namespace invasim::lua
