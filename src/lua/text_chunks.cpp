#include "lua/text_chunks.hpp"

#include <lua.hpp>

#include <stdexcept>

namespace invasim::lua {

namespace {

// Runs once per state with the original load and loadfile as arguments. Trailing arguments
// (`...`) are passed on as given, so that load(s, name, mode, nil) still sets a nil _ENV.
constexpr char kTextOnly[] = R"lua(
local raw_load, raw_loadfile, searchpath = ...
local function text_mode(fname, mode)
  if mode == nil or mode == "t" or mode == "bt" or mode == "tb" then return "t" end
  error(string.format("%s: mode %s refused: invasim loads Lua chunks as text only " ..
                      "(mode 't'; precompiled chunks are not accepted)",
                      fname, type(mode) == "string" and ("'" .. mode .. "'") or tostring(mode)), 3)
end
load = function(chunk, chunkname, mode, ...)
  return raw_load(chunk, chunkname, text_mode("load", mode), ...)
end
-- A refused binary file is named in the message ("attempt to load a binary chunk" alone
-- does not say which file).
local function named(filename, f, err)
  if not f and type(err) == "string" and err:find("binary chunk", 1, true) then
    err = string.format("%s: %s: invasim loads Lua source files only",
                        tostring(filename or "stdin"), err)
  end
  return f, err
end
loadfile = function(filename, mode, ...)
  return named(filename, raw_loadfile(filename, text_mode("loadfile", mode), ...))
end
dofile = function(filename)
  local f, err = named(filename, raw_loadfile(filename, "t"))
  if not f then error(err, 0) end
  return f()
end
package.searchers[2] = function(name)
  local path, err = searchpath(name, package.path)
  if not path then return err end
  local f, lerr = named(path, raw_loadfile(path, "t"))
  if not f then
    error(string.format("error loading module '%s' from file '%s':\n\t%s", name, path, lerr), 0)
  end
  return f, path
end
)lua";

}  // namespace

void restrict_to_text_chunks(lua_State* L) {
  if (luaL_loadbufferx(L, kTextOnly, sizeof(kTextOnly) - 1, "=invasim.text_chunks", "t") != LUA_OK)
    throw std::logic_error("text-only loaders do not compile");
  lua_getglobal(L, "load");
  lua_getglobal(L, "loadfile");
  lua_getglobal(L, "package");
  lua_getfield(L, -1, "searchpath");
  lua_remove(L, -2);
  if (lua_pcall(L, 3, 0, 0) != LUA_OK) {
    lua_pop(L, 1);
    throw std::logic_error("cannot install the text-only loaders");
  }
}

}  // namespace invasim::lua
