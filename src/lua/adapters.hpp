#pragma once
// Method adapters: a bound type's one-value methods as entries of its method list, so that a
// getter is a line, not a function (binding.hpp describes the rest of a binding):
//
//   define_type<Group>(L, {
//       getter<Group, [](const Group& g) { return g.sites.size(); }>("size"),
//       {"name", &lua_wrap<&l_name>},
//   });
//
// Each entry is wrapped with lua_wrap (errors become Lua errors with the caller's location).
#include <concepts>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "lua/binding.hpp"

namespace invasim::lua {

// Pushes one C++ value as its Lua counterpart: numbers, integers, booleans, strings, a bound
// object (binding.hpp's push), a vector of numbers as a list, and an empty optional as nil.
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
void push_value(lua_State* L, const std::string& v);
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
  push_value(L, Get(check<T>(L, 1)));
  return 1;
}
template <typename T, auto Table, auto Params>
int get_params(lua_State* L) {
  Table().push_params(L, Params(check<T>(L, 1)));
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

}  // namespace invasim::lua
