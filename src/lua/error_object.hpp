#pragma once
// What a Lua error says when its error object is not a string: error({}), error(nil),
// error(42), a table with __tostring. Lua itself only says "(error object is a table value)",
// with no place; this names the place where it was raised, the type and, if any, the text.
struct lua_State;

namespace invasim::lua {

// Message handler for lua_pcall (argument 1: the error object). A string and the stop
// sentinel are returned as they are; any other object becomes the string
//   "p.lua:3: error object is a table value (no message)"
//   "p.lua:3: error object is a table value: <its __tostring>"
//   "p.lua:3: error object is a number value: 42"
// where p.lua:3 is the innermost Lua function on the stack (the caller of error()).
// A __tostring that fails is reported as such instead of failing the handler.
int describe_error_object(lua_State* L);

}  // namespace invasim::lua
