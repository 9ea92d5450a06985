// JSON text from Lua values (io/json.hpp: nlohmann-json values, invasim's layout):
//   invasim.json_encode(value [, {indent = 2}]) -> text ending in a newline
//   invasim.read_json(path) -> the file's value as Lua data (objects and arrays as tables,
//                              integers as integers, other numbers as floats, null as nil)
// Tables whose keys are exactly 1..#t (and empty tables) become arrays, read in order up to
// the first nil; other tables become objects with their keys as text (tostring), sorted.
// Lua integers stay integers, floats follow json_float's rule (NaN, inf -> null); userdata
// and functions become their tostring text. __pairs is honoured (read-only parameter tables).
#include <lua.hpp>

#include <vector>

#include "io/json.hpp"
#include "lua/binding.hpp"
#include "lua/engine_types.hpp"
#include "lua/kwargs.hpp"
#include "lua/module.hpp"

namespace invasim::lua {

namespace {

constexpr int kMaxDepth = 256;

// tostring(value at `index`), honouring __tostring (protected: it may raise).
std::string tostring_of(lua_State* L, int index) {
  if (!lua_checkstack(L, 4)) throw LuaApiError("Lua stack overflow");
  lua_pushvalue(L, index);
  protected_call(L, 1, 1, [](lua_State* S) noexcept {
    luaL_tolstring(S, 1, nullptr);
    return 1;
  });
  std::size_t size = 0;
  const char* text = lua_tolstring(L, -1, &size);  // a string: no conversion, no raise
  std::string out(text, size);
  lua_pop(L, 1);
  return out;
}

// #t, honouring __len (protected).
lua_Integer length_of(lua_State* L, int index) {
  if (!lua_checkstack(L, 4)) throw LuaApiError("Lua stack overflow");
  lua_pushvalue(L, index);
  protected_call(L, 1, 1, [](lua_State* S) noexcept {
    lua_pushinteger(S, luaL_len(S, 1));
    return 1;
  });
  const lua_Integer n = lua_tointeger(L, -1);
  lua_pop(L, 1);
  return n;
}

Json to_json(lua_State* L, int index, int depth);

// One key/value pair of a table.
struct Entry {
  bool integer = false;  // an integer key (candidate array index)
  lua_Integer index = 0;
  std::string key;  // the key as text
  Json value;
};

// Adds the pair with the key at `key` and the value at `value` (absolute indices).
void add_entry(lua_State* L, int key, int value, int depth, std::vector<Entry>& out) {
  Entry e;
  e.integer = lua_isinteger(L, key);
  if (e.integer) e.index = lua_tointeger(L, key);
  e.key = lua_type(L, key) == LUA_TSTRING ? std::string(lua_tostring(L, key), lua_rawlen(L, key))
                                          : tostring_of(L, key);
  e.value = to_json(L, value, depth + 1);
  out.push_back(std::move(e));
}

// The pairs of the table at `index` (absolute), as pairs(t) yields them.
std::vector<Entry> entries_of(lua_State* L, int index, int depth) {
  std::vector<Entry> out;
  if (!lua_checkstack(L, 10)) throw LuaApiError("Lua stack overflow");
  lua_pushvalue(L, index);
  protected_call(L, 1, 1, [](lua_State* S) noexcept {
    if (luaL_getmetafield(S, 1, "__pairs") == LUA_TNIL) lua_pushnil(S);
    return 1;
  });
  if (lua_isnil(L, -1)) {  // a plain table: lua_next
    lua_pop(L, 1);
    lua_pushnil(L);
    while (lua_next(L, index)) {
      const int top = lua_gettop(L);
      add_entry(L, top - 1, top, depth, out);
      lua_pop(L, 1);
    }
    return out;
  }
  lua_pushvalue(L, index);  // __pairs(t) -> iterator, state, control
  call_lua(L, 1, 3);
  // Calling a number would fail inside the pcall with no place to name: refused here, at the
  // script's line (a table or userdata may be callable through __call).
  if (const int type = lua_type(L, -3);
      type != LUA_TFUNCTION && type != LUA_TTABLE && type != LUA_TUSERDATA)
    fail_input("json_encode: a table's __pairs returned a ", lua_typename(L, type),
               " where pairs needs an iterator function");
  while (true) {
    for (int k = 0; k < 3; ++k) lua_pushvalue(L, -3);
    call_lua(L, 2, 2);  // iterator(state, control) -> key, value
    const int top = lua_gettop(L);
    if (lua_isnil(L, top - 1)) {
      lua_pop(L, 5);
      return out;
    }
    add_entry(L, top - 1, top, depth, out);
    lua_pop(L, 1);
    lua_replace(L, -2);  // the key is the next control value
  }
}

Json table_to_json(lua_State* L, int index, int depth) {
  if (depth > kMaxDepth)
    fail_input("json_encode: tables nested deeper than ", kMaxDepth,
               " levels (does a table contain itself?)");
  std::vector<Entry> entries = entries_of(L, index, depth);
  const lua_Integer n = length_of(L, index);
  bool array = n > 0 || entries.empty();
  for (const Entry& e : entries) array = array && e.integer && e.index >= 1 && e.index <= n;
  if (array) {  // ipairs order, up to the first missing index
    std::vector<Json*> slot(entries.size(), nullptr);
    for (Entry& e : entries)
      if (std::size_t(e.index) <= slot.size()) slot[std::size_t(e.index) - 1] = &e.value;
    Json out = Json::array();
    for (Json* v : slot) {
      if (!v) break;
      out.push_back(std::move(*v));
    }
    return out;
  }
  Json out = Json::object();
  for (Entry& e : entries) out[e.key] = std::move(e.value);
  return out;
}

Json to_json(lua_State* L, int index, int depth) {
  switch (lua_type(L, index)) {
    case LUA_TNIL:
    case LUA_TNONE:
      return nullptr;
    case LUA_TBOOLEAN:
      return lua_toboolean(L, index) != 0;
    case LUA_TNUMBER:
      if (lua_isinteger(L, index)) return std::int64_t(lua_tointeger(L, index));
      return double(lua_tonumber(L, index));
    case LUA_TSTRING:
      return std::string(lua_tostring(L, index), lua_rawlen(L, index));
    case LUA_TTABLE:
      return table_to_json(L, lua_absindex(L, index), depth);
    default:  // userdata (ramps, groups), functions: their description
      return tostring_of(L, index);
  }
}

int l_json_encode(lua_State* L) {
  int indent = 2;
  if (!lua_isnoneornil(L, 2)) {
    Kwargs kw(L, 2, "json_encode");
    indent = kw.integer<int>("indent", indent, Range::between(0, 16));
    kw.finish();
  }
  const std::string text = json_dump(to_json(L, 1, 0), indent);
  push_value(L, text);
  return 1;
}

// Pushes a JSON value as Lua data (inside protected_call: Lua API calls only; references into
// the Json tree create no C++ object). Returns false if the nesting is too deep.
bool push_json(lua_State* L, const Json& value, int depth) noexcept {
  if (depth > kMaxDepth || !lua_checkstack(L, 3)) return false;
  switch (value.type()) {
    case Json::value_t::object:
      lua_createtable(L, 0, int(value.size()));
      for (auto it = value.begin(); it != value.end(); ++it) {
        const std::string& key = it.key();
        lua_pushlstring(L, key.data(), key.size());
        if (!push_json(L, it.value(), depth + 1)) return false;
        lua_rawset(L, -3);
      }
      return true;
    case Json::value_t::array: {
      lua_createtable(L, int(value.size()), 0);
      lua_Integer i = 0;
      for (const Json& element : value) {
        if (!push_json(L, element, depth + 1)) return false;
        lua_rawseti(L, -2, ++i);
      }
      return true;
    }
    case Json::value_t::string: {
      const std::string& text = value.get_ref<const std::string&>();
      lua_pushlstring(L, text.data(), text.size());
      return true;
    }
    case Json::value_t::boolean:
      lua_pushboolean(L, value.get<bool>() ? 1 : 0);
      return true;
    case Json::value_t::number_integer:
      lua_pushinteger(L, lua_Integer(value.get<std::int64_t>()));
      return true;
    case Json::value_t::number_unsigned:
      if (value.get<std::uint64_t>() <= std::uint64_t(LUA_MAXINTEGER))
        lua_pushinteger(L, lua_Integer(value.get<std::uint64_t>()));
      else
        lua_pushnumber(L, lua_Number(value.get<std::uint64_t>()));
      return true;
    case Json::value_t::number_float:
      lua_pushnumber(L, value.get<double>());
      return true;
    default:  // null, discarded, binary
      lua_pushnil(L);
      return true;
  }
}

int l_read_json(lua_State* L) {
  const std::string path = arg_path(L, 1);
  const Json value = engine_call("read_json", [&] { return read_json(path); });
  bool ok = true;
  push_results(L, 1, [&value, &ok](lua_State* S) noexcept {
    ok = push_json(S, value, 0);  // on success, the value is on top
    if (!ok) lua_pushnil(S);
    return 1;
  });
  if (!ok)
    throw InputError("read_json: " + path + ": nested deeper than " + std::to_string(kMaxDepth) +
                     " levels");
  return 1;
}

}  // namespace

void open_json(lua_State* L) {
  add_functions(L, {INVASIM_LUA_FN(json_encode), INVASIM_LUA_FN(read_json)});
}

}  // namespace invasim::lua
