#include "lua/binding.hpp"

#include <algorithm>
#include <mutex>
#include <vector>

#include "core/names.hpp"
#include "lua/adapters.hpp"
#include "lua/error_object.hpp"
#include "lua/kwargs.hpp"

namespace invasim::lua {

namespace {
// Registry keys of the tables {[C function] = its name}: every bound type's methods, and the
// module's functions (see running_function).
char method_names_key;
char function_names_key;

// Records names[f] = "name" for each function of the list (in the registry table at `key`).
void record_names(lua_State* L, char* key, const luaL_Reg* functions) {
  if (lua_rawgetp(L, LUA_REGISTRYINDEX, key) != LUA_TTABLE) {
    lua_pop(L, 1);
    lua_newtable(L);
    lua_pushvalue(L, -1);
    lua_rawsetp(L, LUA_REGISTRYINDEX, key);
  }
  for (const luaL_Reg* f = functions; f->name != nullptr; ++f) {
    lua_pushcfunction(L, f->func);
    lua_pushstring(L, f->name);
    lua_rawset(L, -3);
  }
  lua_pop(L, 1);
}
}  // namespace

void add_functions(lua_State* L, std::initializer_list<luaL_Reg> functions) {
  const RegList list(functions);
  luaL_setfuncs(L, list.data(), 0);
  record_names(L, &function_names_key, list.data());
}

void push_string_list(lua_State* L, const std::vector<std::string>& items) {
  protected_call(L, 0, 1, [&items](lua_State* S) noexcept {
    push_list(S, items.size(),
              [&](std::size_t k) { lua_pushlstring(S, items[k].data(), items[k].size()); });
    return 1;
  });
}

void push_value(lua_State* L, const std::string& v) {
  protected_call(L, 0, 1, [&v](lua_State* S) noexcept {
    lua_pushlstring(S, v.data(), v.size());
    return 1;
  });
}

void push_record_table(lua_State* S, const Record& record) noexcept {
  lua_createtable(S, 0, static_cast<int>(record.size()));
  for (const RecordEntry& e : record) {
    push_record_value(S, e.value);
    lua_setfield(S, -2, e.key.c_str());
  }
}

void push_record_value(lua_State* S, const RecordValue& value) noexcept {
  std::visit(
      [S](const auto& x) {
        using V = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<V, double>)
          lua_pushnumber(S, x);
        else if constexpr (std::is_same_v<V, long long>)
          lua_pushinteger(S, x);
        else if constexpr (std::is_same_v<V, bool>)
          lua_pushboolean(S, x);
        else if constexpr (std::is_same_v<V, std::string>)
          lua_pushlstring(S, x.data(), x.size());
        else if constexpr (std::is_same_v<V, std::vector<double>>)
          push_list(S, x.size(), [&](std::size_t k) { lua_pushnumber(S, x[k]); });
        else if constexpr (std::is_same_v<V, std::vector<bool>>)
          push_list(S, x.size(), [&](std::size_t k) { lua_pushboolean(S, x[k]); });
        else if constexpr (std::is_same_v<V, std::vector<std::string>>)
          push_list(S, x.size(),
                    [&](std::size_t k) { lua_pushlstring(S, x[k].data(), x[k].size()); });
        else if constexpr (std::is_same_v<V, Vec3>)
          push_list(S, 3, [&](std::size_t k) { lua_pushnumber(S, x[int(k)]); });
        else if constexpr (std::is_same_v<V, Record>)
          push_record_table(S, x);
        else
          push_list(S, x.size(), [&](std::size_t k) { push_record_table(S, x[k]); });
      },
      value.v);
}

int push_record(lua_State* L, const Record& record) {
  return push_results(L, 1, [&record](lua_State* S) noexcept {
    push_record_table(S, record);
    return 1;
  });
}

int push_records(lua_State* L, const std::vector<Record>& records) {
  return push_results(L, 1, [&records](lua_State* S) noexcept {
    push_list(S, records.size(), [&](std::size_t k) { push_record_table(S, records[k]); });
    return 1;
  });
}

int kw_function(Kwargs& kw, std::string_view key) {
  lua_State* L = kw.state();
  const int type = kw.push(key);
  if (type == LUA_TFUNCTION) return lua_gettop(L);
  if (type != LUA_TNIL)
    fail_input(kw.owner(), ": key '", key, "' must be a function, got ", type_name_at(L, -1));
  lua_pop(L, 1);
  return 0;
}

namespace {
// The iterator of hidden_table_pairs: next(t, k) with raw access.
int raw_next(lua_State* L) {
  lua_settop(L, 2);
  if (lua_next(L, 1) != 0) return 2;
  lua_pushnil(L);
  return 1;
}
}  // namespace

int hidden_table_pairs(lua_State* L) {
  lua_pushcfunction(L, &raw_next);
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_pushnil(L);
  return 3;
}

void push_where(lua_State* L) {
  lua_Debug ar;
  for (int level = 1; lua_getstack(L, level, &ar); ++level) {
    lua_getinfo(L, "Sl", &ar);
    if (ar.currentline > 0) {
      lua_pushfstring(L, "%s:%d: ", ar.short_src, ar.currentline);
      return;
    }
  }
  lua_pushliteral(L, "");
}

namespace detail {

namespace {
std::mutex tags_mutex;
std::vector<const TypeTag*>& registered_tags() {
  static std::vector<const TypeTag*> tags;
  return tags;
}
}  // namespace

void register_tag(const TypeTag* tag) {
  std::lock_guard lock(tags_mutex);
  auto& tags = registered_tags();
  if (std::find(tags.begin(), tags.end(), tag) == tags.end()) tags.push_back(tag);
}

const TypeTag* tag_at(lua_State* L, int index) {
  if (lua_type(L, index) != LUA_TUSERDATA || lua_rawlen(L, index) != kUserdataSize) return nullptr;
  UserdataHeader header;
  std::memcpy(&header, lua_touserdata(L, index), sizeof header);
  std::lock_guard lock(tags_mutex);
  const auto& tags = registered_tags();
  return std::find(tags.begin(), tags.end(), header.tag) != tags.end() ? header.tag : nullptr;
}

int gc(lua_State* L) {
  if (const TypeTag* tag = tag_at(L, 1))
    tag->destroy(static_cast<unsigned char*>(lua_touserdata(L, 1)) + kPayloadOffset);
  return 0;
}

}  // namespace detail

// Type name of a value: a bound object's type from its tag ("Progress"), "userdata" for a
// foreign userdata dressed in an invasim metatable, the __name of other userdata ("FILE*"),
// else the Lua type.
std::string type_name_at(lua_State* L, int index) {
  if (lua_type(L, index) == LUA_TNONE) return "no value";
  if (const TypeTag* tag = detail::tag_at(L, index)) return tag->name;
  const int field = luaL_getmetafield(L, index, "__name");  // pushes nothing if absent
  if (field == LUA_TSTRING) {
    std::string name = lua_tostring(L, -1);
    lua_pop(L, 1);
    if (name.rfind("invasim.", 0) == 0) return luaL_typename(L, index);
    return name;
  }
  if (field != LUA_TNIL) lua_pop(L, 1);
  return luaL_typename(L, index);
}

namespace {

// The name recorded for the function on top of the stack in the registry table at `key`
// (record_names), or "". Never raises.
std::string recorded_name(lua_State* L, char* key) {
  std::string name;
  if (lua_rawgetp(L, LUA_REGISTRYINDEX, key) == LUA_TTABLE) {
    lua_pushvalue(L, -2);
    if (lua_rawget(L, -2) == LUA_TSTRING) name = lua_tostring(L, -1);
    lua_pop(L, 1);  // the name (or nil)
  }
  lua_pop(L, 1);  // the table (or what stood in its place)
  return name;
}

// The name of the running C function and whether it was called as a method (obj:f()). When
// Lua cannot name it (called through pcall or as t[k](...)), a bound method is named from the
// method table, and taken as called with its object as argument 1, and a module function
// ("save_checkpoint") from the module's. Never raises.
std::string running_function(lua_State* L, bool& method) {
  std::string function = "?";
  method = false;
  lua_Debug ar;
  if (lua_getstack(L, 0, &ar)) {
    lua_getinfo(L, "nf", &ar);                        // "f" pushes the function
    if (ar.name && std::strcmp(ar.name, "?") != 0) {  // "?": called as t[k](...)
      function = ar.name;
      method = ar.namewhat && std::strcmp(ar.namewhat, "method") == 0;
    } else if (std::string name = recorded_name(L, &method_names_key); !name.empty()) {
      function = name;
      method = true;
    } else if (std::string name = recorded_name(L, &function_names_key); !name.empty()) {
      function = name;
    }
    lua_pop(L, 1);  // the function
  }
  return function;
}

}  // namespace

std::string bad_argument(lua_State* L, int arg, const std::string& expected,
                         const std::string& got_text) {
  const std::string got = got_text.empty() ? type_name_at(L, arg) : got_text;
  bool method = false;
  const std::string function = running_function(L, method);
  if (method && --arg == 0)
    return "bad self for '" + function + "' (" + expected + " expected, got " + got +
           "; call methods with ':', as in obj:" + function + "(...))";
  return "bad argument #" + std::to_string(arg) + " to '" + function + "' (" + expected +
         " expected, got " + got + ")";
}

void no_arguments_after(lua_State* L, int count) {
  for (int arg = count + 1; arg <= lua_gettop(L); ++arg)
    if (!lua_isnil(L, arg)) throw InputError(bad_argument(L, arg, "no value"));
}

namespace detail {

std::string wrong_type_message(lua_State* L, int index, const char* expected) {
  std::string message = bad_argument(L, index, expected);
  bool method = false;
  const std::string function = running_function(L, method);
  if (lua_type(L, index) == LUA_TUSERDATA) {
    // A bound object of another type, or a userdata dressed in our metatable: name the
    // position plainly (the method-call hints of bad_argument would mislead).
    const std::string what = type_name_at(L, index);
    if (method && index == 1)
      return "bad self for '" + function + "' (" + expected + " expected, got " + what + ")";
    return "bad argument #" + std::to_string(method ? index - 1 : index) + " to '" + function +
           "' (" + expected + " expected, got " + what + ")";
  }
  // Most likely obj.method(...) for obj:method(...); a "bad self" already says to use ':'.
  if (index == 1 && !method && message.back() == ')')
    message.insert(message.size() - 1, "; for a method call write obj:method(...)");
  return message;
}

}  // namespace detail

namespace {
char stop_token;  // its address identifies the stop sentinel
}  // namespace

void push_stop_sentinel(lua_State* L) {
  lua_pushlightuserdata(L, &stop_token);
}

bool is_stop_sentinel(lua_State* L, int index) {
  return lua_type(L, index) == LUA_TLIGHTUSERDATA && lua_touserdata(L, index) == &stop_token;
}

double arg_number(lua_State* L, int index) {
  if (lua_type(L, index) != LUA_TNUMBER) throw InputError(bad_argument(L, index, "number"));
  return lua_tonumber(L, index);
}

long long arg_integer(lua_State* L, int index, long long lo, long long hi) {
  const IntegerBounds bounds{lo, hi};
  long long value = 0;
  std::string got;
  switch (check_integer(L, index, bounds, value, got)) {
    case IntegerCheck::kOk:
      return value;
    case IntegerCheck::kNotNumber:
      throw InputError(bad_argument(L, index, "integer"));
    case IntegerCheck::kNotIntegral:
      throw InputError(bad_argument(L, index, "integer " + bounds.describe(), got));
    case IntegerCheck::kOutOfRange:
      break;
  }
  throw InputError(bad_argument(L, index, "integer " + bounds.describe(), got));
}

std::string arg_string(lua_State* L, int index) {
  if (lua_type(L, index) != LUA_TSTRING) throw InputError(bad_argument(L, index, "string"));
  std::size_t size = 0;
  const char* data = lua_tolstring(L, index, &size);
  return std::string(data, size);
}

std::string arg_path(lua_State* L, int index) {
  std::string path = arg_string(L, index);
  const std::size_t nul = path.find('\0');
  if (nul != std::string::npos)
    throw InputError(
        bad_argument(L, index, "path", cat("a string with a NUL byte at position ", nul + 1)));
  return path;
}

void require_no_nul(const std::string& path, const std::string& what) {
  if (path.find('\0') != std::string::npos)
    fail_input(what, " holds a NUL byte (the system call would stop there)");
}

std::optional<double> opt_number(lua_State* L, int index) {
  if (lua_isnoneornil(L, index)) return std::nullopt;
  return arg_number(L, index);
}

namespace detail {

void throw_protected_error(lua_State* L, int status) {
  std::size_t length = 0;
  const char* text = lua_type(L, -1) == LUA_TSTRING ? lua_tolstring(L, -1, &length) : nullptr;
  std::string message = text
                            ? std::string(text, length)  // whole: NULs included
                            : std::string("(error object is a ") + luaL_typename(L, -1) + " value)";
  lua_pop(L, 1);
  if (status == LUA_ERRRUN) throw LuaRaised(message);
  throw LuaApiError(message);  // LUA_ERRMEM: "not enough memory"
}

}  // namespace detail

void call_lua(lua_State* L, int nargs, int nresults) {
  if (!lua_checkstack(L, 1)) throw LuaApiError("Lua stack overflow");
  // The handler below the function: error({}) in a callback names its place, and the
  // traceback with the callback's frames is kept for --traceback.
  const int handler = lua_gettop(L) - nargs;
  lua_pushcfunction(L, &callback_message_handler);  // a light C function: no allocation
  lua_insert(L, handler);
  const int status = lua_pcall(L, nargs, nresults, handler);
  lua_remove(L, handler);
  if (status == LUA_OK) return;
  if (is_stop_sentinel(L, -1)) {  // invasim.stop() in the callback: the script stops quietly
    lua_pop(L, 1);
    throw StopScript();
  }
  detail::throw_protected_error(L, LUA_ERRRUN);  // as a LuaRaised, whatever the status
}

namespace {

// __index of bound types: the method, or an error naming the valid methods.
int l_index(lua_State* L) {
  lua_pushvalue(L, 2);
  if (lua_rawget(L, lua_upvalueindex(1)) != LUA_TNIL) return 1;
  lua_pop(L, 1);
  const std::string type = lua_tostring(L, lua_upvalueindex(2));
  std::vector<std::string> methods;
  lua_pushnil(L);
  while (lua_next(L, lua_upvalueindex(1)) != 0) {
    lua_pop(L, 1);
    if (lua_type(L, -1) == LUA_TSTRING) methods.emplace_back(lua_tostring(L, -1));
  }
  if (lua_type(L, 2) != LUA_TSTRING)
    throw InputError(type + " has no field of type " + luaL_typename(L, 2) +
                     "; methods: " + join_names(methods));
  const std::string key = lua_tostring(L, 2);
  throw InputError(type + " has no method or field '" + key + "'" + did_you_mean(key, methods) +
                   "; methods: " + join_names(methods));
}

}  // namespace

namespace detail {

void define_metatable(lua_State* L, const char* name, const char* type_name,
                      const luaL_Reg* methods, lua_CFunction gc, lua_CFunction tostring) {
  luaL_newmetatable(L, name);  // also sets __name
  lua_pushcfunction(L, gc);
  lua_setfield(L, -2, "__gc");
  lua_pushcfunction(L, tostring);
  lua_setfield(L, -2, "__tostring");
  lua_newtable(L);
  luaL_setfuncs(L, methods, 0);
  record_names(L, &method_names_key, methods);  // see running_function
  lua_pushstring(L, type_name);
  lua_pushcclosure(L, &lua_wrap<&l_index>, 2);
  lua_setfield(L, -2, "__index");
  lua_pushboolean(L, false);  // getmetatable(obj) returns false: scripts cannot alter it
  lua_setfield(L, -2, "__metatable");
  lua_pop(L, 1);
}

}  // namespace detail

}  // namespace invasim::lua
