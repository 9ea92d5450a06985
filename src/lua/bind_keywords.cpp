// invasim.keywords(stage, given, spec [, level]) -> options: the engine's keyword checking
// (lua/kwargs) for stages written in Lua. `given` is the caller's table (nil: {}), `spec` maps
// every valid key to its declaration, in the form invasim.params also reads
// (lua/declaration.hpp): a bare default or {default, type =, range =, choices =, required =,
// unit =, help =}, with stage-only types ("function", "table", a bound type name such as
// "Ramp", alternatives such as "number|Ramp"). Returns a new table
// with the given values and the defaults of the absent keys. Errors are the constructors'
// ("quench: key 'kT' = -1 is out of range (must be >= 0)", "unknown key 'stpes' (did you mean
// 'steps'?); valid keys: ...") at the stage's caller's file:line (`level` levels above the
// stage; default 1, the stage's direct caller).
#include <lua.hpp>

#include <algorithm>
#include <string>
#include <vector>

#include "core/names.hpp"
#include "core/params.hpp"
#include "lua/binding.hpp"
#include "lua/declaration.hpp"
#include "lua/kwargs.hpp"
#include "lua/module.hpp"

namespace invasim::lua {

namespace {

bool is_plain(const std::string& t) {
  return t == "number" || t == "integer" || t == "string" || t == "boolean";
}

// Whether a value of Lua type `type` (named `name`: "string", "Ramp") is of declared type t.
bool of_type(int type, const std::string& name, const std::string& t) {
  if (t == "number" || t == "integer") return type == LUA_TNUMBER;
  return name == t || (t == "function" && type == LUA_TFUNCTION) ||
         (t == "table" && type == LUA_TTABLE) || (t == "userdata" && type == LUA_TUSERDATA);
}

// Checks given[key] against k (via kw, which marks the key known): a value of a plain type as
// the engine's keys are checked (Kwargs::declared), any other by its type.
void check_value(Kwargs& kw, const Declaration& k) {
  const auto as_plain = [&kw, &k](const std::string& t) {
    Declaration one = k;
    one.types = {t};
    kw.declared(one, k.required);
  };
  const bool one_plain = k.types.size() == 1 && is_plain(k.types[0]);
  const int type = kw.push(k.name);
  const std::string got = type_name_at(kw.state(), -1);
  lua_pop(kw.state(), 1);
  if (type == LUA_TNIL) {
    if (!k.required) return;
    if (one_plain) return as_plain(k.types[0]);  // the engine's "missing required key"
    kw.missing(k.name, k.types.empty() ? "any value" : expected_text(k.types).c_str());
  }
  if (k.types.empty()) return;
  for (const auto& t : k.types)
    if (of_type(type, got, t)) {
      if (is_plain(t)) as_plain(t);
      return;
    }
  if (one_plain) return as_plain(k.types[0]);  // the engine's "must be ..., got ..."
  fail_input(kw.owner(), ": key '", k.name, "' must be ", expected_text(k.types), ", got ", got);
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
  std::vector<Declaration> specs;
  for (const auto& name : names) {
    lua_checkstack(L, 4);
    push_value(L, name);
    lua_rawget(L, 3);
    specs.push_back(read_declaration(L, -1, cat("keywords: ", stage, ": key '", name, "'"), name,
                                     DeclarationUse::kKeyword));
    lua_pop(L, 1);
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
          lua_rawgeti(S, -1, 1);
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
