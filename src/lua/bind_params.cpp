// invasim.params{...}: the protocol's parameter declaration (see docs/lua.md).
//
//   local p = iv.params{
//     N_c  = {1500, unit = "cells", help = "number of cancer cells"},
//     phi  = {0.72, help = "packing fraction"},
//     dt   = {0.05, unit = "tau", range = "(0, inf)"},
//     mode = {"a", choices = {"a", "b"}},
//     seed = 1,                                  -- bare default: no unit, no help
//   }
//
// Each entry is a declaration in the form invasim.keywords also reads (lua/declaration.hpp):
// the type follows the default unless `type = ...` names it; `range` (interval notation) and
// `choices` restrict the values. --set/--seed
// overrides are applied and checked here, before the protocol does anything else, and the
// result is a read-only table.
#include <lua.hpp>

#include <algorithm>

#include "core/names.hpp"
#include "core/params.hpp"
#include "lua/adapters.hpp"
#include "lua/binding.hpp"
#include "lua/context.hpp"
#include "lua/declaration.hpp"
#include "lua/fields.hpp"
#include "lua/kwargs.hpp"
#include "lua/module.hpp"

namespace invasim::lua {

namespace {

// Names of the declared parameters (keys of the values table at `index`).
std::vector<std::string> declared_names(lua_State* L, int index) {
  std::vector<std::string> names;
  lua_pushnil(L);
  while (lua_next(L, index) != 0) {
    lua_pop(L, 1);
    if (lua_type(L, -1) == LUA_TSTRING) names.emplace_back(lua_tostring(L, -1));
  }
  return names;
}

std::string key_text(lua_State* L, int index) {
  return lua_type(L, index) == LUA_TSTRING ? cat("'", lua_tostring(L, index), "'")
                                           : std::string("a ") + luaL_typename(L, index) + " key";
}

// __index of the parameter table: only declared names may be read.
int l_param_index(lua_State* L) {
  lua_pushvalue(L, 2);
  if (lua_rawget(L, lua_upvalueindex(1)) != LUA_TNIL) return 1;
  const auto names = declared_names(L, lua_upvalueindex(1));
  const std::string key = key_text(L, 2);
  fail_input("params: no parameter ", key,
             lua_type(L, 2) == LUA_TSTRING ? did_you_mean(lua_tostring(L, 2), names) : "",
             "; declared: ", names.empty() ? "(none)" : join_names(names));
}

// __newindex: parameters are read-only; they change only from the command line.
int l_param_newindex(lua_State* L) {
  const std::string key = key_text(L, 2);
  lua_pushvalue(L, 2);
  if (lua_rawget(L, lua_upvalueindex(1)) == LUA_TNIL)
    fail_input("params: cannot add ", key, ": the parameter table is read-only");
  fail_input("params: cannot assign ", key, ": parameters are read-only; change them with --set ",
             lua_tostring(L, 2), "=VALUE");
}

// Pushes the read-only proxy of the values table on top of the stack (replacing it); inside a
// protected_call block.
void push_proxy(lua_State* L) noexcept {
  const int values = lua_gettop(L);
  lua_newtable(L);  // proxy
  lua_newtable(L);  // metatable
  lua_pushvalue(L, values);
  lua_pushcclosure(L, &lua_wrap<&l_param_index>, 1);
  lua_setfield(L, -2, "__index");
  lua_pushvalue(L, values);
  lua_pushcclosure(L, &lua_wrap<&l_param_newindex>, 1);
  lua_setfield(L, -2, "__newindex");
  lua_pushvalue(L, values);
  lua_pushcclosure(L, &hidden_table_pairs, 1);
  lua_setfield(L, -2, "__pairs");
  lua_pushboolean(L, false);
  lua_setfield(L, -2, "__metatable");
  lua_setmetatable(L, -2);
  lua_replace(L, values);
}

// A protocol's `seed` also seeds Lua's math.random (Lua 5.4 seeds it from the clock), so that
// a protocol drawing its own random numbers repeats itself for the same seed. Protected: the
// script may have replaced math or math.randomseed (a non-function is left alone; a function
// that fails fails invasim.params with its message).
void seed_lua_random(lua_State* L, const std::vector<Param>& params) {
  for (const Param& p : params) {
    if (p.name != "seed" || !std::holds_alternative<long long>(p.value)) continue;
    const long long seed = std::get<long long>(p.value);
    protected_call(L, 0, 0, [seed](lua_State* S) noexcept {
      lua_getglobal(S, "math");
      if (lua_type(S, -1) == LUA_TTABLE && lua_getfield(S, -1, "randomseed") == LUA_TFUNCTION) {
        lua_pushinteger(S, seed);
        lua_call(S, 1, 0);
      }
      return 0;
    });
  }
}

// invasim.params{...}
int l_params(lua_State* L) {
  ScriptContext& context = script_context(L);
  if (context.params)
    fail_input(
        "params: invasim.params{...} was already called; declare every parameter in one "
        "call");
  if (lua_type(L, 1) != LUA_TTABLE)
    fail_input("params: expected a table of parameters, as in invasim.params{phi = 0.72}; got ",
               luaL_typename(L, 1));
  lua_settop(L, 1);
  std::vector<Param> params;
  lua_pushnil(L);
  while (lua_next(L, 1) != 0) {
    if (lua_type(L, -2) != LUA_TSTRING) {
      const std::string key = lua_isinteger(L, -2) ? cat("[", lua_tointeger(L, -2), "]")
                                                   : std::string("of type ") + luaL_typename(L, -2);
      fail_input("params: unexpected entry ", key, "; ", kDeclarationForm);
    }
    const std::string name = lua_tostring(L, -2);
    params.push_back(read_declaration(L, -1, cat("params: parameter '", name, "'"), name,
                                      DeclarationUse::kParameter)
                         .to_param());
    lua_settop(L, 2);  // keep the key for lua_next
  }
  std::sort(params.begin(), params.end(),
            [](const Param& a, const Param& b) { return a.name < b.name; });

  std::vector<Override> overrides = context.options.overrides;
  if (context.options.seed) overrides.push_back({"seed", *context.options.seed, true});
  apply_overrides(params, overrides);
  context.params = params;
  seed_lua_random(L, params);
  if (context.options.list_params) throw StopScript();

  Record values;
  for (const auto& p : params) values.push_back({p.name, p.value});
  return push_results(L, 1, [&values](lua_State* S) noexcept {
    push_record_table(S, values);
    push_proxy(S);
    return 1;
  });
}

}  // namespace

void open_params(lua_State* L) {
  add_functions(L, {INVASIM_LUA_FN(params)});
}

}  // namespace invasim::lua
