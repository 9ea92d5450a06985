// invasim.keywords(stage, given, spec [, level]) -> options: the engine's keyword checking
// (lua/kwargs) for stages written in Lua. `given` is the caller's table (nil: {}), `spec` maps
// every valid key to either its default (a number, string or boolean: the type follows it) or
// a table {type, default =, range =, choices =, required =, unit =, help =}; type is "number",
// "integer", "string", "boolean", "function", "table", "userdata", "any", a bound type name
// ("Ramp", "Contacts", ...) or alternatives joined by '|' ("number|Ramp"). Returns a new table
// with the given values and the defaults of the absent keys. Errors are the constructors'
// ("quench: key 'kT' = -1 is out of range (must be >= 0)", "unknown key 'stpes' (did you mean
// 'steps'?); valid keys: ...") at the stage's caller's file:line (`level` levels above the
// stage; default 1, the stage's direct caller).
#include <lua.hpp>

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "core/names.hpp"
#include "core/params.hpp"
#include "lua/binding.hpp"
#include "lua/kwargs.hpp"
#include "lua/module.hpp"

namespace invasim::lua {

namespace {

// One key of a spec.
struct KeySpec {
  std::string name;
  std::vector<std::string> types;  // alternatives; empty: any
  std::optional<Range> range;
  std::vector<std::string> choices;
  bool required = false;
};

const std::vector<std::string> kPlainTypes = {"number",   "integer", "string",   "boolean",
                                              "function", "table",   "userdata", "any"};

// Whether t is a plain type or the name of a bound type (its metatable "invasim.<t>" exists).
bool known_type(lua_State* L, const std::string& t) {
  if (std::find(kPlainTypes.begin(), kPlainTypes.end(), t) != kPlainTypes.end()) return true;
  const std::string metatable = "invasim." + t;
  bool found = false;
  protected_call(L, 0, 0, [&metatable, &found](lua_State* S) noexcept {
    found = luaL_getmetatable(S, metatable.c_str()) == LUA_TTABLE;
    lua_pop(S, 1);
    return 0;
  });
  return found;
}

std::vector<std::string> split_types(const std::string& text) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    const auto bar = text.find('|', start);
    out.push_back(text.substr(start, bar == std::string::npos ? std::string::npos : bar - start));
    if (bar == std::string::npos) break;
    start = bar + 1;
  }
  return out;
}

// "a number", "an integer", "a Ramp"; alternatives joined by "or".
std::string expected_text(const std::vector<std::string>& types) {
  std::string out;
  for (const auto& t : types) {
    if (!out.empty()) out += " or ";
    if (t == "Ramp") {  // as the engine's own keys say it
      out += "an invasim.ramp{}";
      continue;
    }
    const bool vowel = !t.empty() && std::string("aeiouAEIOU").find(t[0]) != std::string::npos;
    out += cat(vowel ? "an " : "a ", t);
  }
  return out;
}

// Reads spec[name] (on top of the stack, popped) into a KeySpec.
KeySpec read_key_spec(lua_State* L, const std::string& stage, const std::string& name) {
  KeySpec k;
  k.name = name;
  const int type = lua_type(L, -1);
  if (type == LUA_TNUMBER || type == LUA_TSTRING || type == LUA_TBOOLEAN) {
    k.types = {type == LUA_TNUMBER ? "number" : type == LUA_TSTRING ? "string" : "boolean"};
    lua_pop(L, 1);
    return k;
  }
  const std::string owner = cat("keywords: ", stage, ": spec of key '", name, "'");
  if (type != LUA_TTABLE)
    fail_input(owner, " must be a default value or a table {type, default = ...}, got ",
               type_name_at(L, -1));
  const int top = lua_gettop(L);
  Kwargs entry(L, top, owner);
  if (entry.push_index(1) != LUA_TSTRING)
    fail_input(owner,
               ": its first entry must be the type (\"number\", \"integer\", \"string\", "
               "\"boolean\", \"function\", \"table\", \"userdata\", \"any\", a bound type "
               "name or alternatives such as \"number|Ramp\"), got ",
               type_name_at(L, -1));
  const std::string types = lua_tostring(L, -1);
  lua_pop(L, 1);
  k.types = split_types(types);
  if (std::find(k.types.begin(), k.types.end(), "any") != k.types.end()) k.types.clear();
  for (const auto& t : k.types)
    if (!known_type(L, t))
      fail_input(owner, ": unknown type '", t, "'", did_you_mean(t, kPlainTypes),
                 "; a type is one of ", join_names(kPlainTypes),
                 ", a bound type name (Ramp, Group, Contacts, ...) or alternatives joined by '|'");
  if (const auto range = entry.maybe_string("range")) k.range = parse_range(name, *range);
  if (entry.push("choices") != LUA_TNIL) {
    if (!lua_istable(L, -1)) fail_input(owner, ": choices must be a list of strings");
    const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L, -1));
    for (lua_Integer i = 1; i <= n; ++i) {
      if (lua_rawgeti(L, -1, i) != LUA_TSTRING)
        fail_input(owner, ": choices[", i, "] must be a string");
      k.choices.emplace_back(lua_tostring(L, -1));
      lua_pop(L, 1);
    }
  }
  lua_pop(L, 1);
  k.required = entry.boolean("required", false);
  const bool has_default = entry.has("default");
  entry.string("unit", "");
  entry.string("help", "");
  entry.finish();
  if (k.required && has_default)
    fail_input(owner, ": a key is either required or has a default, not both");
  lua_settop(L, top - 1);
  return k;
}

// Checks given[key] against k (via kw, which marks the key known).
void check_value(Kwargs& kw, const KeySpec& k) {
  lua_State* L = kw.state();
  const std::string& key = k.name;
  if (!kw.has(key)) {
    if (!k.required) return;
    if (k.types.size() == 1 && k.types[0] == "number") {
      kw.number(key, k.range.value_or(Range{}));  // the engine's "missing required key" message
      return;
    }
    const std::string what = k.types.empty() ? "any value" : expected_text(k.types);
    kw.push(key);  // nil
    lua_pop(L, 1);
    fail_input(kw.owner(), ": missing required key '", key, "' (", what, ")");
  }
  if (k.types.empty()) return;
  const int type = kw.push(key);
  const std::string got = type_name_at(L, -1);
  const bool is_number = type == LUA_TNUMBER;
  lua_pop(L, 1);
  for (const auto& t : k.types) {
    if (t == "number" && is_number) {
      kw.maybe_number(key, k.range.value_or(Range{}));
      return;
    }
    if (t == "integer" && is_number) {
      kw.maybe_integer<long long>(key, k.range.value_or(Range{}));
      return;
    }
    if (t == "string" && type == LUA_TSTRING) {
      if (!k.choices.empty()) kw.choice(key, k.choices);
      return;
    }
    if ((t == "boolean" && type == LUA_TBOOLEAN) || (t == "function" && type == LUA_TFUNCTION) ||
        (t == "table" && type == LUA_TTABLE) || (t == "userdata" && type == LUA_TUSERDATA) ||
        t == got)
      return;
  }
  if (k.types.size() == 1 && k.types[0] == "integer") {
    kw.maybe_integer<long long>(key, k.range.value_or(Range{}));  // the engine's message
    return;
  }
  fail_input(kw.owner(), ": key '", key, "' must be ", expected_text(k.types), ", got ", got);
}

// "file:line: " of the function `level` levels above the running C function, or "".
std::string where_at(lua_State* L, int level) {
  lua_Debug ar;
  if (!lua_getstack(L, level, &ar) || !lua_getinfo(L, "Sl", &ar) || ar.currentline <= 0) return "";
  return cat(ar.short_src, ":", ar.currentline, ": ");
}

// The stack level of the stage's caller `level` levels up: the stage is level 1 above this C
// function, unless the stage tail-called invasim.keywords (`return iv.keywords(...)`), which
// removed its frame.
int caller_level(lua_State* L, int level) {
  lua_Debug ar;
  const bool tail = lua_getstack(L, 0, &ar) && lua_getinfo(L, "t", &ar) && ar.istailcall;
  return tail ? level : level + 1;
}

int checked(lua_State* L, const std::string& stage, int level) {
  if (lua_isnoneornil(L, 2)) {
    lua_settop(L, 3);
    protected_call(L, 0, 1, [](lua_State* S) noexcept {
      lua_createtable(S, 0, 0);
      return 1;
    });
    lua_replace(L, 2);
  }
  if (!lua_istable(L, 3))
    fail_input("keywords: ", stage, ": the spec (argument 3) must be a table, got ",
               type_name_at(L, 3));
  lua_settop(L, 3);
  // The spec's keys, sorted (errors come in a fixed order).
  std::vector<std::string> names;
  lua_pushnil(L);
  while (lua_next(L, 3) != 0) {
    lua_pop(L, 1);
    if (lua_type(L, -1) != LUA_TSTRING)
      fail_input("keywords: ", stage, ": spec keys must be strings, got ", type_name_at(L, -1));
    names.emplace_back(lua_tostring(L, -1));
  }
  std::sort(names.begin(), names.end());
  std::vector<KeySpec> specs;
  for (const auto& name : names) {
    lua_checkstack(L, 4);
    lua_pushstring(L, name.c_str());  // an existing key of the spec: interned, no allocation
    lua_rawget(L, 3);
    specs.push_back(read_key_spec(L, stage, name));
  }
  try {
    Kwargs kw(L, 2, stage);
    for (const auto& k : specs) check_value(kw, k);
    kw.finish();
  } catch (const InputError& e) {
    throw LuaRaised(where_at(L, caller_level(L, level)) + e.what());
  }
  lua_settop(L, 3);
  lua_pushvalue(L, 2);
  lua_pushvalue(L, 3);
  protected_call(L, 2, 1, [&names](lua_State* S) noexcept {
    lua_createtable(S, 0, static_cast<int>(names.size()));
    for (const auto& name : names) {
      lua_pushstring(S, name.c_str());
      if (lua_rawget(S, 1) == LUA_TNIL) {
        lua_pop(S, 1);
        lua_pushstring(S, name.c_str());
        if (lua_rawget(S, 2) == LUA_TTABLE) {
          lua_pushliteral(S, "default");
          lua_rawget(S, -2);
          lua_remove(S, -2);
        }
      }
      lua_setfield(S, -2, name.c_str());
    }
    return 1;
  });
  return 1;
}

int l_keywords(lua_State* L) {
  if (lua_type(L, 1) != LUA_TSTRING)
    throw InputError(bad_argument(L, 1, "string (the stage's name)"));
  const std::string stage = lua_tostring(L, 1);
  int level = 1;
  if (!lua_isnoneornil(L, 4)) level = static_cast<int>(arg_integer(L, 4, 0, 100));
  if (lua_gettop(L) > 4) lua_settop(L, 4);
  if (!lua_isnoneornil(L, 2) && !lua_istable(L, 2))
    throw LuaRaised(where_at(L, caller_level(L, level)) + stage +
                    ": expected a keyword table, as in " + stage + "{key = value, ...}; got " +
                    type_name_at(L, 2));
  return checked(L, stage, level);
}

}  // namespace

void open_keywords(lua_State* L) {
  add_functions(L, {INVASIM_LUA_FN(keywords)});
}

}  // namespace invasim::lua
