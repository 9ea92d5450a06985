#include "sweep/spec_sandbox.hpp"

#include <lua.hpp>

#include "core/errors.hpp"
#include "lua/error_object.hpp"
#include "lua/stop_hook.hpp"

namespace invasim::sweep {

namespace {

// Builds the spec's environment from the full globals (argument 1) and returns it.
constexpr char kSpecEnvironment[] = R"lua(
local G = ...
local env = {}
for _, name in ipairs{ "assert", "error", "ipairs", "next", "pairs", "pcall", "rawequal",
                       "rawget", "rawlen", "select", "tonumber", "tostring", "type", "xpcall",
                       "_VERSION" } do
  env[name] = G[name]
end
for _, lib in ipairs{ "string", "table", "math", "utf8" } do
  local copy = {}
  for k, v in pairs(G[lib]) do copy[k] = v end
  env[lib] = copy
end
local refused = {}
for _, name in ipairs{ "io", "os", "require", "package", "load", "loadfile", "dofile", "debug",
                       "collectgarbage", "setmetatable", "getmetatable", "rawset", "print",
                       "coroutine", "warn" } do
  refused[name] = true
end
return setmetatable(env, { __index = function(_, name)
  if refused[name] then
    error(string.format("'%s' is not available in a sweep spec: a spec only returns the table " ..
                        "of its sweep (protocol, set, product, zip, seeds, prep, tiny) and may " ..
                        "use the basic functions and the string, table, math and utf8 libraries",
                        tostring(name)), 2)
  end
end, __metatable = false })
)lua";

}  // namespace

void run_spec_chunk(lua_State* L, const std::string& path) {
  lua::install_stop_hook(L);
  lua_pushcfunction(L, &lua::describe_error_object);
  const int handler = lua_gettop(L);
  if (luaL_loadfilex(L, path.c_str(), "t") != LUA_OK) {
    std::string message = lua_tostring(L, -1);
    lua_settop(L, handler - 1);
    if (message.find("binary chunk") != std::string::npos)  // Lua does not name the file
      message = "sweep spec " + path + ": " + message + ": specs are Lua source files only";
    fail_input(message);
  }
  if (luaL_loadbufferx(L, kSpecEnvironment, sizeof(kSpecEnvironment) - 1, "=invasim.spec_env",
                       "t") != LUA_OK)
    throw std::logic_error("the sweep spec environment does not compile");
  lua_pushglobaltable(L);
  if (lua_pcall(L, 1, 1, 0) != LUA_OK) throw std::logic_error("cannot build the spec environment");
  if (lua_setupvalue(L, -2, 1) == nullptr)  // the chunk's _ENV
    throw std::logic_error("a loaded chunk has no _ENV upvalue");
  if (lua_pcall(L, 0, 1, handler) != LUA_OK) {
    const std::string message =
        lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : std::string("error in a spec");
    lua_settop(L, handler - 1);
    fail_input(message);
  }
  lua_remove(L, handler);
}

}  // namespace invasim::sweep
