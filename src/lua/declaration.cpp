#include "lua/declaration.hpp"

#include <lua.hpp>

#include <cmath>

#include "core/errors.hpp"
#include "core/names.hpp"
#include "lua/binding.hpp"
#include "lua/kwargs.hpp"

namespace invasim::lua {

namespace {

const std::vector<std::string> kPlainTypes = {"number", "integer", "string", "boolean"};
const std::vector<std::string> kKeywordTypes = {"number",   "integer", "string",   "boolean",
                                                "function", "table",   "userdata", "any"};

// Whether t is a keyword type: a plain one or a bound type's name (metatable "invasim.<t>").
bool known_type(lua_State* L, const std::string& t) {
  if (contains(kKeywordTypes, t)) return true;
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
    if (bar == std::string::npos) return out;
    start = bar + 1;
  }
}

// The type a default at `index` gives a declaration that names none.
std::string type_of_default(lua_State* L, int index) {
  switch (lua_type(L, index)) {
    case LUA_TNUMBER:
      return lua_isinteger(L, index) ? "integer" : "number";
    case LUA_TFUNCTION:
      return "function";
    case LUA_TTABLE:
      return "table";
    default:
      return type_name_at(L, index);  // string, boolean, or a bound type's name
  }
}

// Whether the value at `index` is of type t (an integral float is an integer).
bool matches(lua_State* L, int index, const std::string& t) {
  const int type = lua_type(L, index);
  if (t == "integer") {
    if (type != LUA_TNUMBER) return false;
    const double x = lua_tonumber(L, index);
    constexpr double kTwo63 = 9223372036854775808.0;  // the integers a long long holds
    return lua_isinteger(L, index) || (x == std::floor(x) && x >= -kTwo63 && x < kTwo63);
  }
  if (t == "number") return type == LUA_TNUMBER;
  if (t == "function") return type == LUA_TFUNCTION;
  if (t == "table") return type == LUA_TTABLE;
  if (t == "userdata") return type == LUA_TUSERDATA;
  return t == type_name_at(L, index);
}

// The `choices = {"a", "b"}` on top of the stack (a non-empty list of strings).
std::vector<std::string> read_choices(lua_State* L, const std::string& owner) {
  const auto bad = [&] {
    fail_input(owner, ": key 'choices' must be a list of strings, as in choices = {\"a\", \"b\"}");
  };
  if (lua_type(L, -1) != LUA_TTABLE) bad();
  std::vector<std::string> choices;
  const auto n = static_cast<lua_Integer>(lua_rawlen(L, -1));
  for (lua_Integer i = 1; i <= n; ++i) {
    if (lua_rawgeti(L, -1, i) != LUA_TSTRING) bad();
    choices.emplace_back(lua_tostring(L, -1));
    lua_pop(L, 1);
  }
  // Only the list part: any other key (choices = {a = 1}) is a mistake.
  lua_pushnil(L);
  while (lua_next(L, -2) != 0) {
    lua_pop(L, 1);
    if (!lua_isinteger(L, -1) || lua_tointeger(L, -1) < 1 || lua_tointeger(L, -1) > n) bad();
  }
  if (choices.empty()) bad();
  return choices;
}

// The default at `index` as a plain value of type t ("number", "integer", "string", "boolean").
ParamValue plain_value(lua_State* L, int index, const std::string& t) {
  if (t == "number") return double(lua_tonumber(L, index));
  if (t == "integer")  // a Lua integer as it is (beyond 2^53 a double would round it)
    return lua_isinteger(L, index) ? static_cast<long long>(lua_tointeger(L, index))
                                   : static_cast<long long>(lua_tonumber(L, index));
  if (t == "boolean") return bool(lua_toboolean(L, index));
  std::size_t size = 0;
  const char* data = lua_tolstring(L, index, &size);
  return std::string(data, size);
}

// The declared types: `type = ...` when given, else the default's.
std::vector<std::string> declared_types(lua_State* L, const std::optional<std::string>& type,
                                        int value, const std::string& owner, bool parameter) {
  if (!type) {
    if (lua_isnil(L, value))
      fail_input(owner, parameter ? " has no default; " : " has neither a type nor a default; ",
                 kDeclarationForm, parameter ? "" : " or name = {type = \"number\", ...}");
    return {type_of_default(L, value)};
  }
  const auto types = split_types(*type);
  for (const auto& t : types) {
    const bool ok = parameter ? contains(kPlainTypes, t) && types.size() == 1 : known_type(L, t);
    if (!ok)
      fail_input(owner, ": unknown type '", *type, "'",
                 did_you_mean(t, parameter ? kPlainTypes : kKeywordTypes), "; a type is one of ",
                 join_names(parameter ? kPlainTypes : kKeywordTypes),
                 parameter ? ""
                           : ", a bound type name (Ramp, Group, ...) or alternatives "
                             "joined by '|'");
  }
  if (contains(types, "any")) return {};
  return types;
}

// The default at `value` against the declared types; sets d.default_value when it is plain.
void check_default(lua_State* L, int value, Declaration& d, const std::string& owner,
                   bool parameter) {
  const int type = lua_type(L, value);
  const bool plain = type == LUA_TNUMBER || type == LUA_TSTRING || type == LUA_TBOOLEAN;
  if (parameter && !plain)
    fail_input(owner, " has a ", luaL_typename(L, value),
               " default; defaults are numbers, integers, booleans or strings");
  if (type == LUA_TNUMBER && !std::isfinite(lua_tonumber(L, value)))
    fail_input(owner, " has a non-finite default");
  if (d.types.empty()) {
    if (plain) d.default_value = plain_value(L, value, type_of_default(L, value));
    return;
  }
  for (const auto& t : d.types)
    if (matches(L, value, t)) {
      if (contains(kPlainTypes, t)) d.default_value = plain_value(L, value, t);
      return;
    }
  if (d.types.size() == 1 && d.types[0] == "integer" && type == LUA_TNUMBER)
    fail_input(owner, " is declared an integer but its default ", lua_tonumber(L, value),
               " is not");
  fail_input(owner, " is declared type = '", join_names(d.types), "' but its default is ",
             expected_text({type_of_default(L, value)}));
}

// Range only on numbers, choices only on strings, a plain default inside them.
void check_rules(const Declaration& d, const std::string& owner, bool parameter) {
  const auto has = [&d](const char* t) { return d.types.empty() || contains(d.types, t); };
  const char* noun = parameter ? "parameters" : "keys";
  const std::string types = d.type_text();
  if (d.range && !has("number") && !has("integer"))
    fail_input(owner, " is a ", types, ": a range applies to number and integer ", noun, " only");
  if (!d.choices.empty() && !has("string"))
    fail_input(owner, " is a ", types, ": choices apply to string ", noun, " only");
  if (d.default_value)
    if (const std::string why = default_violation(d.to_param()); !why.empty())
      fail_input(owner, " ", why);
}

}  // namespace

Param Declaration::to_param() const {
  Param p;
  p.name = name;
  if (default_value) {
    p.default_value = *default_value;
    p.type = std::visit(
        [](const auto& v) {
          using V = std::decay_t<decltype(v)>;
          if constexpr (std::is_same_v<V, double>) return ParamType::kNumber;
          if constexpr (std::is_same_v<V, long long>) return ParamType::kInteger;
          if constexpr (std::is_same_v<V, bool>) return ParamType::kBoolean;
          return ParamType::kString;
        },
        *default_value);
  }
  p.value = p.default_value;
  p.unit = unit;
  p.help = help;
  p.range = range;
  p.choices = choices;
  return p;
}

std::string Declaration::type_text() const {
  if (!list_form.empty()) return list_form;
  std::string out;
  for (const auto& t : types) out += (out.empty() ? "" : " or ") + t;
  return out;
}

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

Declaration read_declaration(lua_State* L, int index, const std::string& owner,
                             const std::string& name, DeclarationUse use) {
  index = lua_absindex(L, index);
  const bool parameter = use == DeclarationUse::kParameter;
  const int top = lua_gettop(L);
  Declaration d;
  d.name = name;
  std::optional<std::string> type;
  int value = index;  // where the default is
  const int kind = lua_type(L, index);
  if (kind == LUA_TTABLE) {
    Kwargs entry(L, index, owner);
    d.unit = entry.string("unit", "");
    d.help = entry.string("help", "");
    type = entry.maybe_string("type");
    if (const auto range = entry.maybe_string("range")) d.range = parse_range(name, *range);
    if (entry.push("choices") != LUA_TNIL) d.choices = read_choices(L, owner);
    lua_pop(L, 1);
    if (!parameter) d.required = entry.boolean("required", false);
    entry.push_index(1);
    value = lua_gettop(L);
    entry.finish();
  }
  d.has_default = !lua_isnil(L, value);
  if (d.required && d.has_default)
    fail_input(owner, ": a key is either required or has a default, not both");
  d.types = declared_types(L, type, value, owner, parameter);
  if (d.has_default) check_default(L, value, d, owner, parameter);
  check_rules(d, owner, parameter);
  lua_settop(L, top);
  return d;
}

}  // namespace invasim::lua
