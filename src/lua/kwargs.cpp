#include "lua/kwargs.hpp"

#include <lua.hpp>

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"
#include "core/names.hpp"
#include "core/params.hpp"
#include "lua/binding.hpp"

namespace invasim::lua {

namespace {

// Shown after "got": the value for numbers (1.5), the type name otherwise.
std::string got(lua_State* L, int index) {
  if (lua_type(L, index) == LUA_TNUMBER) {
    if (lua_isinteger(L, index)) return std::to_string(lua_tointeger(L, index));
    return format_number(lua_tonumber(L, index));
  }
  return type_name_at(L, index);
}

// The declaration a typed getter checks: one plain type, finite numbers only.
Declaration plain_declaration(std::string_view key, const char* type, Range range = {}) {
  return field_declaration(std::string(key), {type}, shown_range(range, false), "", "");
}

}  // namespace

Kwargs::Kwargs(lua_State* L, int index, std::string owner)
    : L_(L), index_(lua_absindex(L, index)), owner_(std::move(owner)) {
  if (lua_type(L, index_) != LUA_TTABLE)
    fail_input(owner_, ": expected a keyword table, as in ", owner_, "{key = value, ...}; got ",
               type_name_at(L, index_));
}

int Kwargs::push(std::string_view key) {
  if (std::find(known_.begin(), known_.end(), key) == known_.end()) known_.emplace_back(key);
  // Creating the key string allocates (a Lua error when memory runs out): protected, since
  // this Kwargs owns C++ strings.
  if (!lua_checkstack(L_, 4)) throw LuaApiError("Lua stack overflow");
  lua_pushvalue(L_, index_);
  protected_call(L_, 1, 1, [key](lua_State* S) noexcept {
    lua_pushlstring(S, key.data(), key.size());
    lua_rawget(S, 1);
    return 1;
  });
  return lua_type(L_, -1);
}

int Kwargs::fetch_present(std::string_view key) {
  const int type = push(key);
  if (type == LUA_TNIL) lua_pop(L_, 1);
  return type;
}

void Kwargs::type_error(std::string_view key, const char* expected) const {
  fail_input(owner_, ": key '", key, "' must be ", expected, ", got ", got(L_, -1));
}

// Value on top of the stack -> finite number in range; pops it.
double Kwargs::to_number(std::string_view key, Range range) {
  if (lua_type(L_, -1) != LUA_TNUMBER) type_error(key, "a number");
  const double value = lua_tonumber(L_, -1);
  if (!std::isfinite(value)) type_error(key, "a finite number");
  if (!range.contains(value))
    fail_input(owner_, ": key '", key, "' = ", format_number(value), " is out of range (must be ",
               range.describe(), ")");
  lua_pop(L_, 1);
  return value;
}

// Value on top of the stack -> integer within bounds (integral floats such as 2e5 accepted);
// pops it.
long long Kwargs::to_integer(std::string_view key, const IntegerBounds& bounds) {
  long long value = 0;
  std::string text;
  switch (check_integer(L_, -1, bounds, value, text)) {
    case IntegerCheck::kOk:
      break;
    case IntegerCheck::kNotNumber:
    case IntegerCheck::kNotIntegral: {
      fail_input(owner_, ": key '", key, "' must be an integer, got ", text,
                 bounds.any() ? "" : " (allowed: " + bounds.describe() + ")");
    }
    case IntegerCheck::kOutOfRange:
      fail_input(owner_, ": key '", key, "' = ", text, " is out of range (must be ",
                 bounds.describe(), ")");
  }
  lua_pop(L_, 1);
  return value;
}

IntegerBounds IntegerBounds::of(const Range& range, long long type_lo, long long type_hi) {
  // 2^63 as a double: every bound at or beyond it is outside long long anyway.
  constexpr double kTwo63 = 9223372036854775808.0;
  IntegerBounds b{type_lo, type_hi};
  if (range.lo >= kTwo63) {
    b.lo = std::numeric_limits<long long>::max();
  } else if (range.lo > -kTwo63) {
    double lo = std::ceil(range.lo);
    if (range.lo_open && lo == range.lo) lo += 1.0;
    if (lo < kTwo63) b.lo = std::max(b.lo, static_cast<long long>(lo));
  }
  if (range.hi <= -kTwo63) {
    b.hi = std::numeric_limits<long long>::min();
  } else if (range.hi < kTwo63) {
    double hi = std::floor(range.hi);
    if (range.hi_open && hi == range.hi) hi -= 1.0;
    if (hi >= -kTwo63) b.hi = std::min(b.hi, static_cast<long long>(hi));
  }
  return b;
}

std::string IntegerBounds::describe() const {
  const bool has_lo = lo > std::numeric_limits<long long>::min();
  const bool has_hi = hi < std::numeric_limits<long long>::max();
  if (has_lo && has_hi) return "in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  if (has_lo) return ">= " + std::to_string(lo);
  if (has_hi) return "<= " + std::to_string(hi);
  return "any integer";
}

IntegerCheck check_integer(lua_State* L, int index, const IntegerBounds& bounds, long long& value,
                           std::string& text) {
  text = got(L, index);
  if (lua_type(L, index) != LUA_TNUMBER) return IntegerCheck::kNotNumber;
  if (lua_isinteger(L, index)) {
    value = lua_tointeger(L, index);
    return bounds.contains(value) ? IntegerCheck::kOk : IntegerCheck::kOutOfRange;
  }
  const double x = lua_tonumber(L, index);
  if (!std::isfinite(x) || x != std::floor(x)) return IntegerCheck::kNotIntegral;
  // Compared as doubles first: a float such as 1e12 or 1e300 may not fit the target type or
  // even a long long; the conversion happens only inside the bounds.
  if (x < static_cast<double>(bounds.lo) || x > static_cast<double>(bounds.hi))
    return IntegerCheck::kOutOfRange;
  if (x >= 9223372036854775808.0) return IntegerCheck::kOutOfRange;  // 2^63 (bound rounded up)
  value = static_cast<long long>(x);
  return bounds.contains(value) ? IntegerCheck::kOk : IntegerCheck::kOutOfRange;
}

void Kwargs::missing(std::string_view key, const char* expected) const {
  // A misspelt key is more useful to name than the missing one alone: look for a key of the
  // table that nobody asked for and that is close to `key`.
  std::string typo;
  const std::vector<std::string> wanted{std::string(key)};
  lua_checkstack(L_, 3);
  lua_pushnil(L_);
  while (lua_next(L_, index_) != 0) {
    lua_pop(L_, 1);
    if (lua_type(L_, -1) != LUA_TSTRING) continue;
    const std::string candidate = lua_tostring(L_, -1);
    if (std::find(known_.begin(), known_.end(), candidate) == known_.end() &&
        !did_you_mean(candidate, wanted).empty())
      typo = candidate;
  }
  if (!typo.empty())
    fail_input(owner_, ": missing required key '", key, "' (", expected, "); unknown key '", typo,
               "' (did you mean '", key, "'?)");
  fail_input(owner_, ": missing required key '", key, "' (", expected, ")");
}

bool Kwargs::to_boolean(std::string_view key) {
  if (lua_type(L_, -1) != LUA_TBOOLEAN) type_error(key, "a boolean (true or false)");
  const bool value = lua_toboolean(L_, -1);
  lua_pop(L_, 1);
  return value;
}

std::string Kwargs::to_string(std::string_view key) {
  if (lua_type(L_, -1) != LUA_TSTRING) type_error(key, "a string");
  std::size_t size = 0;
  const char* data = lua_tolstring(L_, -1, &size);
  std::string value(data, size);
  lua_pop(L_, 1);
  return value;
}

std::optional<ParamValue> Kwargs::declared(const Declaration& d, bool required,
                                           std::optional<IntegerBounds> bounds) {
  const std::string& key = d.name;
  const std::string& type = d.types.at(0);
  const Range range = d.range.value_or(Range{});
  if (type == "integer" && !bounds) bounds = IntegerBounds::of<long long>(range);
  if (fetch_present(key) == LUA_TNIL) {
    if (!required) return std::nullopt;
    std::string expected = type == "number" ? "a number" : "true or false";
    if (type == "integer") {
      expected = bounds->any() ? "an integer" : "an integer " + bounds->describe();
    } else if (type == "string") {
      expected = d.choices.empty() ? "a string" : "one of: " + join_names(d.choices);
    }
    missing(key, expected.c_str());
  }
  if (type == "number") {
    if (lua_type(L_, -1) == LUA_TNUMBER && lua_tonumber(L_, -1) == HUGE_VAL &&
        range.contains(HUGE_VAL)) {
      lua_pop(L_, 1);
      return HUGE_VAL;
    }
    return to_number(key, range);
  }
  if (type == "integer") return to_integer(key, *bounds);
  if (type == "boolean") return to_boolean(key);
  std::string value = to_string(key);
  if (!d.choices.empty() && std::find(d.choices.begin(), d.choices.end(), value) == d.choices.end())
    fail_input(owner_, ": key '", key, "' must be one of: ", join_names(d.choices), "; got '",
               value, "'", did_you_mean(value, d.choices));
  return value;
}

double Kwargs::number(std::string_view key, Range range) {
  return std::get<double>(*declared(plain_declaration(key, "number", range), true));
}

bool Kwargs::boolean(std::string_view key) {
  return std::get<bool>(*declared(plain_declaration(key, "boolean"), true));
}

std::string Kwargs::string(std::string_view key) {
  return std::get<std::string>(*declared(plain_declaration(key, "string"), true));
}

double Kwargs::number(std::string_view key, double fallback, Range range) {
  return maybe_number(key, range).value_or(fallback);
}

bool Kwargs::boolean(std::string_view key, bool fallback) {
  const auto value = declared(plain_declaration(key, "boolean"), false);
  return value ? std::get<bool>(*value) : fallback;
}

std::string Kwargs::string(std::string_view key, const std::string& fallback) {
  return maybe_string(key).value_or(fallback);
}

std::optional<double> Kwargs::maybe_number(std::string_view key, Range range) {
  const auto value = declared(plain_declaration(key, "number", range), false);
  if (!value) return std::nullopt;
  return std::get<double>(*value);
}

std::optional<long long> Kwargs::integer_value(std::string_view key, Range range,
                                               const IntegerBounds& bounds, bool required) {
  const auto value = declared(plain_declaration(key, "integer", range), required, bounds);
  if (!value) return std::nullopt;
  return std::get<long long>(*value);
}

std::optional<std::string> Kwargs::maybe_string(std::string_view key) {
  auto value = declared(plain_declaration(key, "string"), false);
  if (!value) return std::nullopt;
  return std::get<std::string>(std::move(*value));
}

std::optional<std::vector<double>> Kwargs::maybe_number_list(std::string_view key, std::size_t size,
                                                             Range range) {
  const int type = fetch_present(key);
  if (type == LUA_TNIL) return std::nullopt;
  const std::string expected = "a list of " + std::to_string(size) + " numbers";
  if (type != LUA_TTABLE) type_error(key, expected.c_str());
  const std::size_t length = lua_rawlen(L_, -1);
  if (length != size)
    fail_input(owner_, ": key '", key, "' must be ", expected, ", got a table of length ", length);
  std::vector<double> values(size);
  for (std::size_t i = 0; i < size; ++i) {
    lua_rawgeti(L_, -1, static_cast<lua_Integer>(i + 1));
    const std::string element = std::string(key) + "[" + std::to_string(i + 1) + "]";
    values[i] = to_number(element, range);
  }
  lua_pop(L_, 1);
  return values;
}

std::vector<double> Kwargs::number_list(std::string_view key, std::size_t size, Range range) {
  auto values = maybe_number_list(key, size, range);
  if (!values) missing(key, cat("a list of ", size, " numbers").c_str());
  return std::move(*values);
}

std::optional<std::vector<bool>> Kwargs::maybe_boolean_list(std::string_view key,
                                                            std::size_t size) {
  const int type = fetch_present(key);
  if (type == LUA_TNIL) return std::nullopt;
  const std::string expected = "a list of " + std::to_string(size) + " booleans";
  if (type != LUA_TTABLE || lua_rawlen(L_, -1) != size) type_error(key, expected.c_str());
  std::vector<bool> values(size);
  for (std::size_t i = 0; i < size; ++i) {
    if (lua_rawgeti(L_, -1, static_cast<lua_Integer>(i + 1)) != LUA_TBOOLEAN) {
      const std::string element = std::string(key) + "[" + std::to_string(i + 1) + "]";
      type_error(element, "a boolean (true or false)");
    }
    values[i] = lua_toboolean(L_, -1);
    lua_pop(L_, 1);
  }
  lua_pop(L_, 1);
  return values;
}

std::optional<Kwargs> Kwargs::maybe_table(std::string_view key) {
  const int type = fetch_present(key);
  if (type == LUA_TNIL) return std::nullopt;
  if (type != LUA_TTABLE) type_error(key, "a keyword table");
  return Kwargs(L_, -1, owner_ + "." + std::string(key));
}

int Kwargs::push_index(int i) {
  positional_allowed_ = std::max(positional_allowed_, i);
  lua_checkstack(L_, 1);
  return lua_rawgeti(L_, index_, i);
}

bool Kwargs::has(std::string_view key) {
  const bool present = push(key) != LUA_TNIL;
  lua_pop(L_, 1);
  return present;
}

void Kwargs::finish() const {
  std::vector<std::string> unknown, positional;
  lua_checkstack(L_, 3);
  lua_pushnil(L_);
  while (lua_next(L_, index_) != 0) {
    lua_pop(L_, 1);  // the value; the key stays for lua_next
    if (lua_type(L_, -1) == LUA_TSTRING) {
      std::size_t size = 0;
      const char* data = lua_tolstring(L_, -1, &size);
      std::string key(data, size);
      if (std::find(known_.begin(), known_.end(), key) == known_.end()) unknown.push_back(key);
    } else if (lua_isinteger(L_, -1)) {
      const lua_Integer i = lua_tointeger(L_, -1);
      if (i >= 1 && i <= positional_allowed_) continue;
      positional.push_back(cat("[", i, "]"));
    } else {
      positional.push_back("a " + std::string(luaL_typename(L_, -1)) + " key");
    }
  }
  const std::string valid =
      known_.empty() ? "it takes no keys" : "valid keys: " + join_names(known_);
  if (!unknown.empty()) {
    std::sort(unknown.begin(), unknown.end());
    if (unknown.size() == 1)
      fail_input(owner_, ": unknown key '", unknown[0], "'", did_you_mean(unknown[0], known_), "; ",
                 valid);
    std::string list;
    for (const auto& key : unknown) list += (list.empty() ? "'" : ", '") + key + "'";
    fail_input(owner_, ": unknown keys ", list, "; ", valid);
  }
  if (!positional.empty()) {
    std::sort(positional.begin(), positional.end());
    fail_input(owner_, ": unexpected positional value ", positional[0], "; write key = value (",
               valid, ")");
  }
}

}  // namespace invasim::lua
