#pragma once
// Reading a keyword table, as constructors take them: `invasim.System{box = {...}, seed = 7}`.
// Typed getters check type and range and remember every key they were asked about; finish()
// then rejects any other key, listing the valid ones. Every failure is an InputError whose
// message names the owner and the key ("System: key 'seed' must be an integer, got string");
// lua_wrap adds the script location. Values are read with raw access (no metamethods run).
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "core/range.hpp"
#include "lua/declaration.hpp"

struct lua_State;

namespace invasim::lua {

// The integers of type T as a closed interval of long long (lua_Integer): unsigned types above
// LLONG_MAX are capped there.
template <typename T>
constexpr long long integer_type_min() {
  static_assert(std::is_integral_v<T> && sizeof(T) <= sizeof(long long));
  return std::is_signed_v<T> ? static_cast<long long>(std::numeric_limits<T>::min()) : 0;
}
template <typename T>
constexpr long long integer_type_max() {
  static_assert(std::is_integral_v<T> && sizeof(T) <= sizeof(long long));
  if constexpr (sizeof(T) < sizeof(long long) || std::is_signed_v<T>)
    return static_cast<long long>(std::numeric_limits<T>::max());
  else
    return std::numeric_limits<long long>::max();
}

// The integers in `range` that a T can hold, as a closed interval [lo, hi] of long long.
struct IntegerBounds {
  long long lo, hi;
  static IntegerBounds of(const Range& range, long long type_lo, long long type_hi);
  template <typename T>
  static IntegerBounds of(const Range& range) {
    return of(range, integer_type_min<T>(), integer_type_max<T>());
  }
  bool contains(long long x) const { return x >= lo && x <= hi; }
  // Whether every long long is in: no bound to state in messages.
  bool any() const {
    return lo == std::numeric_limits<long long>::min() &&
           hi == std::numeric_limits<long long>::max();
  }
  // ">= 0", "in [0, 2147483647]" (a side at the long long limit is left out).
  std::string describe() const;
};

// The value at `index` as an integer within bounds, checked before any narrowing: an
// integral float (2e5) is accepted; `got` receives the text of a refused value ("2.5",
// "4294967301", "string"). Never raises a Lua error.
enum class IntegerCheck { kOk, kNotNumber, kNotIntegral, kOutOfRange };
IntegerCheck check_integer(lua_State* L, int index, const IntegerBounds& bounds, long long& value,
                           std::string& got);

class Kwargs {
 public:
  // Reads the table at `index`; `owner` names what is being built ("System"). Throws if the
  // value there is not a table.
  Kwargs(lua_State* L, int index, std::string owner);

  // The one check of a key against its declaration (one plain type): nullopt when absent and
  // not `required`; else the value, checked against the type, the range (a number range
  // closed at +inf, "[0, inf]", also takes math.huge) and the choices. `bounds`: the integers
  // the C++ type that stores an integer key can hold (default: a long long's). Every typed
  // getter below, FieldTable's keys (lua/fields.hpp) and invasim.keywords check through it.
  std::optional<ParamValue> declared(const Declaration& d, bool required,
                                     std::optional<IntegerBounds> bounds = std::nullopt);

  // Required keys: absent (or nil) is an error.
  double number(std::string_view key, Range range = {});
  bool boolean(std::string_view key);
  std::string string(std::string_view key);

  // Keys with a default.
  double number(std::string_view key, double fallback, Range range = {});
  bool boolean(std::string_view key, bool fallback);
  std::string string(std::string_view key, const std::string& fallback);

  // Optional keys: nullopt when absent.
  std::optional<double> maybe_number(std::string_view key, Range range = {});

  // Integer keys read as the C++ type T they are stored in (int, std::size_t, ...): the range
  // is required, and the Lua value is checked against range ∩ T before it is converted, so
  // that 2^32 + 5 is refused instead of becoming 5 in an int.
  template <typename T>
  T integer(std::string_view key, Range range) {
    return static_cast<T>(*integer_value(key, range, IntegerBounds::of<T>(range), true));
  }
  template <typename T>
  T integer(std::string_view key, T fallback, Range range) {
    const auto value = maybe_integer<T>(key, range);
    return value ? *value : fallback;
  }
  template <typename T>
  std::optional<T> maybe_integer(std::string_view key, Range range) {
    const auto value = integer_value(key, range, IntegerBounds::of<T>(range), false);
    if (!value) return std::nullopt;
    return static_cast<T>(*value);
  }
  std::optional<std::string> maybe_string(std::string_view key);

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

  // Throws "missing required key 'box' (expected)", naming a misspelt key of the table if there
  // is one ("; unknown key 'bxo' (did you mean 'box'?)").
  [[noreturn]] void missing(std::string_view key, const char* expected) const;

 private:
  // push(key), but an absent key (nil) leaves nothing on the stack.
  int fetch_present(std::string_view key);
  [[noreturn]] void type_error(std::string_view key, const char* expected) const;
  // The value on top of the stack as the type named; pops it.
  double to_number(std::string_view key, Range range);
  long long to_integer(std::string_view key, const IntegerBounds& bounds);
  bool to_boolean(std::string_view key);
  std::string to_string(std::string_view key);
  std::optional<long long> integer_value(std::string_view key, Range range,
                                         const IntegerBounds& bounds, bool required);

  lua_State* L_;
  int index_;
  std::string owner_;
  std::vector<std::string> known_;
  int positional_allowed_ = 0;  // t[1..n] accepted by finish()
};

}  // namespace invasim::lua
