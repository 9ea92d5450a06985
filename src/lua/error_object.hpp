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

// Message handler of Lua callbacks run from C++ (call_lua): describes the error object as
// describe_error_object does and records, in the registry, the message with the traceback
// of the stack where it was raised, the callback's frames included. A binding re-raises the
// same message after the callback's pcall has unwound those frames, so the script's own
// handler (LuaState) shows the recorded traceback instead (take_callback_traceback). A message
// already recorded (a callback inside a callback) keeps its innermost traceback.
int callback_message_handler(lua_State* L);

// Pushes the traceback recorded for `message` by callback_message_handler and forgets it;
// returns false (nothing pushed) when none is recorded for this message. Allocates: for
// message handlers and protected code only.
bool take_callback_traceback(lua_State* L, int message);

}  // namespace invasim::lua
