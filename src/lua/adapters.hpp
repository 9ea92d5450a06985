#pragma once
// Adapters that make a binding a declarative list (binding.hpp describes the rest):
//
//   define_type<Dynamics>(L, {
//       getter<Dynamics, [](const Dynamics& d) { return d.dt(); }>("dt"),
//       method<"set_dt", [](Dynamics& d, double dt) { d.set_dt(dt); }>(),
//       {"run", &lua_wrap<&l_run>},          // anything longer stays a function
//   });
//   return push_record(L, {{"A_t", m.area}, {"counts", counts}});   // a result table
//
// method<> reads each positional argument by its C++ type (Arg<T>), runs the body through
// engine_call (an engine InputError gets the method's name in front) and pushes what it
// returns with push_value. Every entry is wrapped with lua_wrap.
#include <algorithm>
#include <concepts>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "core/vec3.hpp"
#include "lua/binding.hpp"
#include "lua/kwargs.hpp"

namespace invasim::lua {

// Pushes one C++ value as its Lua counterpart: numbers, integers, booleans, strings (binding.hpp),
// a bound object (binding.hpp's push), a vector of numbers as a list, and an empty optional as nil.
inline void push_value(lua_State* L, double v) {
  lua_pushnumber(L, v);
}
template <std::integral I>
requires(!std::same_as<I, bool>) void push_value(lua_State* L, I v) {
  lua_pushinteger(L, static_cast<lua_Integer>(v));
}
inline void push_value(lua_State* L, bool v) {
  lua_pushboolean(L, v);
}
template <typename U>
void push_value(lua_State* L, const std::shared_ptr<U>& object) {  // a bound object
  push(L, object);
}
template <typename V>
requires std::is_arithmetic_v<V>
void push_value(lua_State* L, const std::vector<V>& v) {
  protected_call(L, 0, 1, [&v](lua_State* S) noexcept {
    push_list(S, v.size(), [&](std::size_t k) { push_value(S, v[k]); });
    return 1;
  });
}
inline void push_value(lua_State* L, const std::vector<std::string>& v) {
  push_string_list(L, v);
}
template <typename V>
void push_value(lua_State* L, const std::optional<V>& v) {
  if (v)
    push_value(L, *v);
  else
    lua_pushnil(L);
}

namespace detail {
template <typename T, auto Get>
int get_value(lua_State* L) {
  const T& object = check<T>(L, 1);
  no_arguments_after(L, 1);
  push_value(L, Get(object));
  return 1;
}
template <typename T, auto Table, auto Params>
int get_params(lua_State* L) {
  const T& object = check<T>(L, 1);
  no_arguments_after(L, 1);
  Table().push_params(L, Params(object));
  return 1;
}
}  // namespace detail

// obj:name() -> Get(obj), pushed by push_value.
template <typename T, auto Get>
constexpr luaL_Reg getter(const char* name) {
  return {name, &lua_wrap<&detail::get_value<T, Get>>};
}

// obj:name() -> the table of keys of Table() (a FieldTable<P>) read from Params(obj).
template <typename T, auto Table, auto Params>
constexpr luaL_Reg params_method(const char* name) {
  return {name, &lua_wrap<&detail::get_params<T, Table, Params>>};
}

// Runs fn(); an InputError from the engine is rethrown with "owner: " in front (unless the
// message already starts with it), so messages name the Lua call they came from.
template <typename Fn>
decltype(auto) engine_call(std::string_view owner, Fn&& fn) {
  try {
    return fn();
  } catch (const InputError& e) {
    const std::string what = e.what();
    const std::string prefix = std::string(owner) + ": ";
    if (what.rfind(prefix, 0) == 0) throw;
    throw InputError(prefix + what);
  }
}

// A name as a template argument: method<"set_dt", ...>.
template <std::size_t N>
struct Name {
  constexpr Name(const char (&s)[N]) { std::copy_n(s, N, text); }
  char text[N];
};

// Positional argument `index` read as a T: a bound object by reference (check<T>) unless T is
// one of the plain types below. Errors are binding.hpp's "bad argument #2 to 'f' (...)".
template <typename T>
struct Arg {
  static T& read(lua_State* L, int index) { return check<T>(L, index); }
};
template <typename T>
struct Arg<std::shared_ptr<T>> {
  static std::shared_ptr<T> read(lua_State* L, int index) { return check_shared<T>(L, index); }
};
template <>
struct Arg<double> {
  static double read(lua_State* L, int index) { return arg_number(L, index); }
};
template <>
struct Arg<std::string> {
  static std::string read(lua_State* L, int index) { return arg_string(L, index); }
};
// A file or directory argument of a bound function (arg_path).
struct Path {
  std::string value;
};
template <>
struct Arg<Path> {
  static Path read(lua_State* L, int index) { return {arg_path(L, index)}; }
};
template <>
struct Arg<std::optional<double>> {  // a number or nil
  static std::optional<double> read(lua_State* L, int index) { return opt_number(L, index); }
};
template <>
struct Arg<std::uint64_t> {  // a step count or index: an integer >= 0
  static std::uint64_t read(lua_State* L, int index) {
    return std::uint64_t(arg_integer(L, index, 0, std::numeric_limits<long long>::max()));
  }
};

namespace detail {
template <Name N, auto F, typename R, typename... A, std::size_t... I>
int invoke_method(lua_State* L, std::index_sequence<I...>) {
  // Braced initialisation reads the arguments in order; bound objects stay references.
  std::tuple<decltype(Arg<std::remove_cvref_t<A>>::read(L, 1))...> args{
      Arg<std::remove_cvref_t<A>>::read(L, int(I) + 1)...};
  no_arguments_after(L, int(sizeof...(A)));
  if constexpr (std::is_void_v<R>) {
    engine_call(N.text, [&] { std::apply(F, args); });
    return 0;
  } else {
    push_value(L, engine_call(N.text, [&] { return std::apply(F, args); }));
    return 1;
  }
}
template <typename M>
struct MethodOf;
template <typename C, typename R, typename... A>
struct MethodOf<R (C::*)(A...) const> {
  template <Name N, auto F>
  static int call(lua_State* L) {
    return invoke_method<N, F, R, A...>(L, std::index_sequence_for<A...>{});
  }
};
}  // namespace detail

// The list entry N -> F(arguments...), F a lambda without captures (see the top of the file).
template <Name N, auto F>
constexpr luaL_Reg method() {
  using M = detail::MethodOf<decltype(&decltype(F)::operator())>;
  return {N.text, &lua_wrap<&M::template call<N, F>>};
}

// A result table written as a list of {key, value}: numbers, integers, booleans, strings,
// lists of numbers, booleans or strings, vectors {x, y, z}, nested tables and lists of tables.
struct RecordEntry;
using Record = std::vector<RecordEntry>;
struct RecordValue {
  std::variant<double, long long, bool, std::string, std::vector<double>, std::vector<bool>,
               std::vector<std::string>, Vec3, Record, std::vector<Record>>
      v;
  RecordValue(double x) : v(x) {}
  template <std::integral I>
  requires(!std::same_as<I, bool>) RecordValue(I x) : v(static_cast<long long>(x)) {}
  RecordValue(bool x) : v(x) {}
  RecordValue(std::string x) : v(std::move(x)) {}
  RecordValue(const char* x) : v(std::string(x)) {}
  RecordValue(std::vector<double> x) : v(std::move(x)) {}
  RecordValue(std::vector<bool> x) : v(std::move(x)) {}
  RecordValue(std::vector<std::string> x) : v(std::move(x)) {}
  RecordValue(const Vec3& x) : v(x) {}
  RecordValue(Record x);
  RecordValue(std::vector<Record> x) : v(std::move(x)) {}
  RecordValue(const ParamValue& x)
      : v(std::visit([](const auto& y) -> decltype(v) { return y; }, x)) {}
};
struct RecordEntry {
  std::string key;
  RecordValue value;
};
inline RecordValue::RecordValue(Record x) : v(std::move(x)) {}

// Pushes the table of `record` (protected: may be called anywhere); returns 1 for `return`.
int push_record(lua_State* L, const Record& record);
// The same for a list of tables.
int push_records(lua_State* L, const std::vector<Record>& records);
// The same inside a protected_call block (they allocate; a Lua error there is caught).
void push_record_table(lua_State* S, const Record& record) noexcept;
void push_record_value(lua_State* S, const RecordValue& value) noexcept;

// The bound T of key `key` of kw (nullptr when absent and not required): "run: key 'progress'
// must be a Progress, got number", "Simulation: missing required key 'system' (a System)";
// `noun` replaces "a Progress" in the messages.
template <typename T>
std::shared_ptr<T> kw_object(Kwargs& kw, std::string_view key, bool required = false,
                             const char* noun = nullptr) {
  lua_State* L = kw.state();
  const int type = kw.push(key);
  std::shared_ptr<T> object;
  if (type == LUA_TNIL && required) {
    lua_pop(L, 1);
    kw.missing(key, (noun ? std::string(noun) : std::string("a ") + LuaType<T>::name).c_str());
  }
  if (type != LUA_TNIL) {
    const auto* slot = test<T>(L, -1);
    if (slot == nullptr || !*slot)
      throw InputError(kw.owner() + ": key '" + std::string(key) + "' must be " +
                       (noun ? std::string(noun) : std::string("a ") + LuaType<T>::name) +
                       ", got " +
                       (slot ? std::string("one no longer valid") : type_name_at(L, -1)));
    object = *slot;
  }
  lua_pop(L, 1);
  return object;
}

// The stack index of the function of key `key` (left on the stack for the caller's lifetime),
// or 0 when absent: "checkpoint: key 'extra' must be a function, got number".
int kw_function(Kwargs& kw, std::string_view key);

}  // namespace invasim::lua
