#include "lua/fields.hpp"

#include <algorithm>
#include <sstream>

#include "core/names.hpp"
#include "lua/binding.hpp"

namespace invasim::lua {

namespace {

// A value as describe() prints it: numbers as an ostream does (0.2, 1e-08), booleans as words.
std::string text_of(const ParamValue& value) {
  if (const auto* d = std::get_if<double>(&value)) return cat(*d);
  if (const auto* b = std::get_if<bool>(&value)) return *b ? "true" : "false";
  return format_value(value);
}

std::map<std::string, std::vector<Declaration>>& registry() {
  static std::map<std::string, std::vector<Declaration>> tables;
  return tables;
}

// __newindex of a read-only table: "file:line: invasim.Contacts.defaults is read-only".
int read_only_newindex(lua_State* L) {
  luaL_where(L, 2);
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_pushliteral(L, " is read-only (copy it into a table of your own to change it)");
  lua_concat(L, 3);
  return lua_error(L);
}

// __call of a constructor table: drops the table itself and calls the constructor (upvalue 1)
// with the remaining arguments. Owns no C++ object, so a Lua error may pass through it.
int call_constructor(lua_State* L) {
  lua_remove(L, 1);
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
  return lua_gettop(L);
}

// Replaces the table on top of the stack by a read-only proxy of it named `name`.
void make_read_only(lua_State* S, const char* name) noexcept {
  lua_createtable(S, 0, 0);  // proxy
  lua_createtable(S, 0, 4);  // its metatable
  lua_pushvalue(S, -3);
  lua_setfield(S, -2, "__index");
  lua_pushstring(S, name);
  lua_pushcclosure(S, &read_only_newindex, 1);
  lua_setfield(S, -2, "__newindex");
  lua_pushvalue(S, -3);
  lua_pushcclosure(S, &hidden_table_pairs, 1);
  lua_setfield(S, -2, "__pairs");
  lua_pushliteral(S, "read-only");
  lua_setfield(S, -2, "__metatable");
  lua_setmetatable(S, -2);
  lua_remove(S, -2);
}

// The allowed values as text: "(0, inf)", "{isotropic, yz}", or "".
std::string allowed_text(const Declaration& f) {
  if (f.range) return f.range->notation();
  if (!f.choices.empty()) return cat("{", join_names(f.choices), "}");
  return "";
}

}  // namespace

void push_param_value(lua_State* S, const ParamValue& value) noexcept {
  if (const auto* d = std::get_if<double>(&value))
    lua_pushnumber(S, *d);
  else if (const auto* i = std::get_if<long long>(&value))
    lua_pushinteger(S, *i);
  else if (const auto* b = std::get_if<bool>(&value))
    lua_pushboolean(S, *b);
  else {
    const std::string& s = std::get<std::string>(value);
    lua_pushlstring(S, s.data(), s.size());
  }
}

namespace fields_detail {

std::string describe(const std::vector<std::pair<std::string, ParamValue>>& values) {
  std::string out;
  for (const auto& [name, value] : values) {
    if (!out.empty()) out += ", ";
    out += name + "=" + text_of(value);
  }
  return out;
}

void push_values(lua_State* L, const std::vector<std::pair<std::string, ParamValue>>& values) {
  protected_call(L, 0, 1, [&values](lua_State* S) noexcept {
    lua_createtable(S, 0, static_cast<int>(values.size()));
    for (const auto& [name, value] : values) {
      push_param_value(S, value);
      lua_setfield(S, -2, name.c_str());
    }
    return 1;
  });
}

}  // namespace fields_detail

namespace {

// The texts of the fields list, computed before any Lua call: each key's type ("number or
// Ramp") and allowed range in interval notation ("" for none).
struct ListTexts {
  std::vector<std::string> types, ranges;
};
ListTexts list_texts(const std::vector<Declaration>& infos) {
  ListTexts out;
  for (const auto& f : infos) {
    out.types.push_back(f.type_text());
    out.ranges.push_back(f.range ? f.range->notation() : "");
  }
  return out;
}

// Pushes the fields list (inside a protected call).
void push_field_list_raw(lua_State* S, const std::vector<Declaration>& infos,
                         const ListTexts& texts) noexcept {
  lua_createtable(S, static_cast<int>(infos.size()), 0);
  for (std::size_t k = 0; k < infos.size(); ++k) {
    const Declaration& f = infos[k];
    lua_createtable(S, 0, 8);
    lua_pushstring(S, f.name.c_str());
    lua_setfield(S, -2, "name");
    lua_pushstring(S, texts.types[k].c_str());
    lua_setfield(S, -2, "type");
    if (f.default_value) {
      push_param_value(S, *f.default_value);
      lua_setfield(S, -2, "default");
    }
    if (!texts.ranges[k].empty()) {
      lua_pushstring(S, texts.ranges[k].c_str());
      lua_setfield(S, -2, "range");
    }
    if (!f.choices.empty()) {
      push_list(S, f.choices.size(),
                [&](std::size_t c) { lua_pushstring(S, f.choices[c].c_str()); });
      lua_setfield(S, -2, "choices");
    }
    lua_pushstring(S, f.unit.c_str());
    lua_setfield(S, -2, "unit");
    lua_pushstring(S, f.help.c_str());
    lua_setfield(S, -2, "help");
    lua_pushboolean(S, f.required);
    lua_setfield(S, -2, "required");
    lua_pushboolean(S, f.state);
    lua_setfield(S, -2, "state");
    lua_rawseti(S, -2, static_cast<lua_Integer>(k + 1));
  }
}

// Pushes the read-only defaults table named `name` (inside a protected call).
void push_defaults_raw(lua_State* S, const std::vector<Declaration>& infos,
                       const std::string& name) noexcept {
  lua_createtable(S, 0, static_cast<int>(infos.size()));
  for (const auto& f : infos) {
    if (!f.default_value) continue;
    push_param_value(S, *f.default_value);
    lua_setfield(S, -2, f.name.c_str());
  }
  make_read_only(S, name.c_str());
}

// Pushes {defaults =, fields =} (inside a protected call).
void push_key_table_raw(lua_State* S, const std::vector<Declaration>& infos, const ListTexts& texts,
                        const std::string& defaults_name) noexcept {
  lua_createtable(S, 0, 2);
  push_defaults_raw(S, infos, defaults_name);
  lua_setfield(S, -2, "defaults");
  push_field_list_raw(S, infos, texts);
  lua_setfield(S, -2, "fields");
}

}  // namespace

void push_field_list(lua_State* L, const std::vector<Declaration>& infos) {
  const ListTexts texts = list_texts(infos);
  protected_call(L, 0, 1, [&infos, &texts](lua_State* S) noexcept {
    push_field_list_raw(S, infos, texts);
    return 1;
  });
}

void push_defaults(lua_State* L, const std::vector<Declaration>& infos, const std::string& name) {
  protected_call(L, 0, 1, [&infos, &name](lua_State* S) noexcept {
    push_defaults_raw(S, infos, name);
    return 1;
  });
}

void set_constructor(lua_State* L, const char* name, lua_CFunction constructor,
                     const std::vector<Declaration>& infos) {
  registry()[name] = infos;
  const std::string defaults_name = cat("invasim.", name, ".defaults");
  const ListTexts texts = list_texts(infos);
  lua_pushvalue(L, -1);  // the module table, argument 1 of the block
  protected_call(L, 1, 0, [&](lua_State* S) noexcept {
    push_key_table_raw(S, infos, texts, defaults_name);
    lua_createtable(S, 0, 1);
    lua_pushcfunction(S, constructor);
    lua_pushcclosure(S, &call_constructor, 1);
    lua_setfield(S, -2, "__call");
    lua_setmetatable(S, -2);
    lua_setfield(S, 1, name);
    return 0;
  });
}

void set_method_keys(lua_State* L, const char* type, const char* method,
                     const std::vector<Declaration>& infos) {
  registry()[cat(type, ":", method)] = infos;
  const std::string defaults_name = cat("invasim.", type, ".", method, ".defaults");
  const ListTexts texts = list_texts(infos);
  lua_pushvalue(L, -1);  // the module table, argument 1 of the block
  protected_call(L, 1, 0, [&](lua_State* S) noexcept {
    lua_getfield(S, 1, type);
    push_key_table_raw(S, infos, texts, defaults_name);
    lua_setfield(S, -2, method);
    return 0;
  });
}

void set_static_function(lua_State* L, const char* type, const char* name, lua_CFunction fn) {
  lua_pushvalue(L, -1);  // the module table, argument 1 of the block
  protected_call(L, 1, 0, [&](lua_State* S) noexcept {
    lua_getfield(S, 1, type);
    lua_pushcfunction(S, fn);
    lua_setfield(S, -2, name);
    return 0;
  });
}

const std::map<std::string, std::vector<Declaration>>& registered_field_tables() {
  return registry();
}

std::string format_field_table(const std::vector<Declaration>& infos) {
  std::vector<std::vector<std::string>> rows = {
      {"key", "type", "default", "allowed", "unit", "meaning"}};
  for (const auto& f : infos) {
    std::string def = f.required ? "required" : "-";
    if (f.default_value)
      def = std::holds_alternative<std::string>(*f.default_value)
                ? cat('"', format_value(*f.default_value), '"')
                : format_value(*f.default_value);
    const std::string allowed = allowed_text(f);
    rows.push_back({f.name, f.type_text(), def, allowed.empty() ? "-" : allowed,
                    f.unit.empty() ? "-" : f.unit, f.help});
  }
  return aligned_table(rows);
}

}  // namespace invasim::lua
