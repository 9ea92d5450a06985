#pragma once
// Reading a keyword table, as constructors take them: `invasim.System{box = {...}, seed = 7}`.
// Typed getters check type and range and remember every key they were asked about; finish()
// then rejects any other key, listing the valid ones. Every failure is an InputError whose
// message names the owner and the key ("System: key 'seed' must be an integer, got string");
// lua_wrap adds the script location. Values are read with raw access (no metamethods run).
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

struct lua_State;

namespace invasim::lua {

// Allowed interval of a numeric keyword; the default allows every finite value.
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false;
  bool hi_open = false;

  static Range positive() { return {0.0, hi_inf(), true, false}; }       // > 0
  static Range non_negative() { return {0.0, hi_inf(), false, false}; }  // >= 0
  static Range at_least(double lo) { return {lo, hi_inf(), false, false}; }
  static Range greater_than(double lo) { return {lo, hi_inf(), true, false}; }
  static Range between(double lo, double hi) { return {lo, hi, false, false}; }  // [lo, hi]

  bool contains(double x) const;
  std::string describe() const;  // "> 0", ">= 1", "in [0, 1]"

 private:
  static double hi_inf() { return std::numeric_limits<double>::infinity(); }
};

class Kwargs {
 public:
  // Reads the table at `index`; `owner` names what is being built ("System"). Throws if the
  // value there is not a table.
  Kwargs(lua_State* L, int index, std::string owner);

  // Required keys: absent (or nil) is an error.
  double number(std::string_view key, Range range = {});
  long long integer(std::string_view key, Range range = {});
  bool boolean(std::string_view key);
  std::string string(std::string_view key);

  // Keys with a default.
  double number(std::string_view key, double fallback, Range range = {});
  long long integer(std::string_view key, long long fallback, Range range = {});
  bool boolean(std::string_view key, bool fallback);
  std::string string(std::string_view key, const std::string& fallback);

  // Optional keys: nullopt when absent.
  std::optional<double> maybe_number(std::string_view key, Range range = {});
  std::optional<long long> maybe_integer(std::string_view key, Range range = {});
  std::optional<bool> maybe_boolean(std::string_view key);
  std::optional<std::string> maybe_string(std::string_view key);

  // A string from a fixed set; the error lists the choices.
  std::string choice(std::string_view key, const std::vector<std::string>& choices,
                     std::optional<std::string> fallback = std::nullopt);

  // A list of exactly `size` numbers ({70, 70, 70}); nullopt when absent and not required.
  std::optional<std::vector<double>> maybe_number_list(std::string_view key, std::size_t size,
                                                       Range range = {});
  std::vector<double> number_list(std::string_view key, std::size_t size, Range range = {});
  std::optional<std::vector<bool>> maybe_boolean_list(std::string_view key, std::size_t size);

  // A nested keyword table: pushes it on the Lua stack (left there for the caller's lifetime)
  // and reads it with owner "owner.key". nullopt when absent.
  std::optional<Kwargs> maybe_table(std::string_view key);

  // Pushes the positional value t[i] (nil when absent) and allows it in finish(); returns
  // its Lua type. For forms such as {0.72, unit = "1"} whose first entry is positional.
  int push_index(int i);

  // Pushes the raw value of `key` (nil when absent), marks the key known, returns its Lua
  // type: for values a binding decodes itself (a userdata, a ramp, a callback).
  int push(std::string_view key);

  // Whether `key` is present (non-nil); also marks it known.
  bool has(std::string_view key);

  // Throws if the table holds any key no getter asked about, or a positional value:
  // "System: unknown key 'bxo' (did you mean 'box'?); valid keys: box, periodic, seed".
  void finish() const;

  const std::string& owner() const { return owner_; }
  lua_State* state() const { return L_; }
  int index() const { return index_; }

 private:
  // Pushes the value of key (raw get) and records the key; returns its Lua type.
  int fetch(std::string_view key);
  [[noreturn]] void type_error(std::string_view key, const char* expected) const;
  // Throws "missing required key", naming a misspelt key of the table if there is one.
  [[noreturn]] void missing(std::string_view key, const char* expected) const;
  double to_number(std::string_view key, Range range);
  long long to_integer(std::string_view key, Range range);
  void check_range(std::string_view key, double value, const Range& range) const;

  lua_State* L_;
  int index_;
  std::string owner_;
  std::vector<std::string> known_;
  int positional_allowed_ = 0;  // t[1..n] accepted by finish()
};

}  // namespace invasim::lua
