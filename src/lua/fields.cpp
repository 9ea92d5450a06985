#include "lua/fields.hpp"

#include <algorithm>
#include <sstream>

#include "core/names.hpp"
#include "lua/adapters.hpp"
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
  Record record;
  for (const auto& [name, value] : values) record.push_back({name, value});
  push_record(L, record);
}

}  // namespace fields_detail

namespace {

// The `invasim.X.fields` list: {name =, type =, default =, range =, choices =, unit =, help =,
// required =, state =} per key.
RecordValue field_records(const std::vector<Declaration>& infos) {
  std::vector<Record> out;
  for (const auto& f : infos) {
    Record r{{"name", f.name}, {"type", f.type_text()},  {"unit", f.unit},
             {"help", f.help}, {"required", f.required}, {"state", f.state}};
    if (f.default_value) r.push_back({"default", *f.default_value});
    if (f.range) r.push_back({"range", f.range->notation()});
    if (!f.choices.empty()) r.push_back({"choices", f.choices});
    out.push_back(std::move(r));
  }
  return out;
}

// The defaults of the keys that have a plain one: {name = default}.
Record default_record(const std::vector<Declaration>& infos) {
  Record out;
  for (const auto& f : infos)
    if (f.default_value) out.push_back({f.name, *f.default_value});
  return out;
}

// Pushes {defaults =, fields =}, the defaults a read-only table named `defaults_name` (inside a
// protected call).
void push_key_table_raw(lua_State* S, const Record& defaults, const RecordValue& fields,
                        const std::string& defaults_name) noexcept {
  lua_createtable(S, 0, 2);
  push_record_table(S, defaults);
  make_read_only(S, defaults_name.c_str());
  lua_setfield(S, -2, "defaults");
  push_record_value(S, fields);
  lua_setfield(S, -2, "fields");
}

}  // namespace

void set_constructor(lua_State* L, const char* name, lua_CFunction constructor,
                     const std::vector<Declaration>& infos) {
  registry()[name] = infos;
  const std::string defaults_name = cat("invasim.", name, ".defaults");
  const Record defaults = default_record(infos);
  const RecordValue fields = field_records(infos);
  lua_pushvalue(L, -1);  // the module table, argument 1 of the block
  protected_call(L, 1, 0, [&](lua_State* S) noexcept {
    push_key_table_raw(S, defaults, fields, defaults_name);
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
  const Record defaults = default_record(infos);
  const RecordValue fields = field_records(infos);
  lua_pushvalue(L, -1);  // the module table, argument 1 of the block
  protected_call(L, 1, 0, [&](lua_State* S) noexcept {
    lua_getfield(S, 1, type);
    push_key_table_raw(S, defaults, fields, defaults_name);
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
