#pragma once
// One declaration per parameter of a bound type. A FieldTable<P> lists the keys of a parameter
// struct P once (name, accessor, range, unit, help; the default is the value in a
// default-constructed P, so the engine struct's own initialiser is the only default), and
// derives from that list the constructor's keyword reader, `obj:set{}`, `obj:params()`, the
// `describe()` text, and what Lua sees as `invasim.X.defaults` and `invasim.X.fields`.
//
//   const FieldTable<ContactParams> kContacts("Contacts", {
//       number<ContactParams>("alpha", &ContactParams::alpha, Range::non_negative(), "1",
//                             "cohesion range: r_a = (1 + alpha) s"), ...});
//   ContactParams p = kContacts.make(kw);   // reads and validates, then kw.finish()
#include <lua.hpp>

#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/params.hpp"
#include "core/range.hpp"
#include "lua/declaration.hpp"
#include "lua/kwargs.hpp"

namespace invasim::lua {

// One key of P: its facts, how to read it from a keyword table into a P, and its value in a P.
template <typename P>
struct Field {
  Declaration info;
  // Reads the key into p. Absent: an error when `required`, else p keeps its value.
  std::function<void(Kwargs&, P&, bool required)> read;
  // The value in p, when it is a plain value (nullopt for a Group).
  std::function<std::optional<ParamValue>(const P&)> value;
};

// Non-template halves of FieldTable (fields.cpp).
namespace fields_detail {
// "alpha=0.2, beta=0" for the state fields (numbers as `cat` prints them).
std::string describe(const std::vector<std::pair<std::string, ParamValue>>& values);
// Pushes {name = value, ...}.
void push_values(lua_State* L, const std::vector<std::pair<std::string, ParamValue>>& values);
}  // namespace fields_detail

// The declared keys of a bound type with parameter struct P.
template <typename P>
class FieldTable {
 public:
  FieldTable(std::string type, std::vector<Field<P>> fields, P defaults = P{})
      : type_(std::move(type)), fields_(std::move(fields)), defaults_(std::move(defaults)) {
    for (auto& f : fields_)
      if (!f.info.required && f.value) {
        f.info.default_value = f.value(defaults_);
        f.info.has_default = f.info.default_value.has_value();
      }
  }

  const std::string& type() const { return type_; }
  const std::vector<Field<P>>& fields() const { return fields_; }
  std::vector<Declaration> infos() const {
    std::vector<Declaration> out;
    for (const auto& f : fields_) out.push_back(f.info);
    return out;
  }

  // Constructor keys: the defaults, overridden by kw; required keys must be present. Does not
  // call kw.finish() (a binding may read further keys first).
  P read(Kwargs& kw) const {
    P p = defaults_;
    for (const auto& f : fields_) f.read(kw, p, f.info.required);
    return p;
  }
  // Constructor keys and nothing else.
  P make(Kwargs& kw) const {
    P p = read(kw);
    kw.finish();
    return p;
  }
  // `obj:set{}`: the state keys present in kw replace p's values; nothing is required.
  void set(Kwargs& kw, P& p) const {
    for (const auto& f : fields_)
      if (f.info.state) f.read(kw, p, false);
    kw.finish();
  }
  // The state fields' values in p, in declaration order.
  std::vector<std::pair<std::string, ParamValue>> values(const P& p) const {
    std::vector<std::pair<std::string, ParamValue>> out;
    for (const auto& f : fields_)
      if (f.info.state && f.value)
        if (auto v = f.value(p)) out.emplace_back(f.info.name, std::move(*v));
    return out;
  }
  // "alpha=0.2, beta=0, ..." and "Contacts(alpha=0.2, ...)".
  std::string describe_fields(const P& p) const { return fields_detail::describe(values(p)); }
  std::string describe(const P& p) const { return type_ + "(" + describe_fields(p) + ")"; }
  // `obj:params()`: pushes {name = value} of the state fields.
  void push_params(lua_State* L, const P& p) const { fields_detail::push_values(L, values(p)); }

 private:
  std::string type_;
  std::vector<Field<P>> fields_;
  P defaults_;
};

// The member (or nested value) a field reads and writes: a member pointer or a lambda P& -> T&.
template <typename P, typename Access>
using FieldRef = std::remove_reference_t<std::invoke_result_t<Access, P&>>;

// A field held in a member of P: its read checks the Lua value against the declaration
// (Kwargs::declared) and hands it to store(member, value); its value is load(member).
template <typename P, typename Access, typename Store, typename Load>
Field<P> member_field(Declaration d, Access access, std::optional<IntegerBounds> bounds,
                      Store store, Load load) {
  Field<P> f;
  f.info = std::move(d);
  f.read = [info = f.info, access, bounds, store](Kwargs& kw, P& p, bool required) {
    if (auto v = kw.declared(info, required, bounds)) store(std::invoke(access, p), std::move(*v));
  };
  f.value = [access, load](const P& p) -> std::optional<ParamValue> {
    return load(std::invoke(access, const_cast<P&>(p)));
  };
  return f;
}

// Stores and loads a member that holds its value as it is (double, bool, std::string).
template <typename T>
constexpr auto kStoreAs = [](T& slot, ParamValue v) { slot = std::get<T>(std::move(v)); };
constexpr auto kLoad = [](const auto& slot) -> std::optional<ParamValue> { return slot; };

// A finite number in `range` (with allow_infinity, also +inf: tau_p = math.huge).
template <typename P, typename Access>
Field<P> number(std::string name, Access access, Range range, std::string unit, std::string help,
                bool allow_infinity = false) {
  return member_field<P>(field_declaration(name, {"number"}, shown_range(range, allow_infinity),
                                           std::move(unit), std::move(help)),
                         access, std::nullopt, kStoreAs<double>, kLoad);
}

// An integer stored as the C++ type of the member (int, std::size_t, std::uint64_t, ...): the
// value is checked against range and that type's integers before it is converted.
template <typename P, typename Access>
Field<P> integer(std::string name, Access access, Range range, std::string unit, std::string help) {
  using T = FieldRef<P, Access>;
  return member_field<P>(
      field_declaration(name, {"integer"}, shown_range(range, false), std::move(unit),
                        std::move(help)),
      access, IntegerBounds::of<T>(range),
      [](T& slot, ParamValue v) { slot = static_cast<T>(std::get<long long>(v)); },
      [](const T& slot) -> std::optional<ParamValue> { return static_cast<long long>(slot); });
}

template <typename P, typename Access>
Field<P> boolean(std::string name, Access access, std::string help) {
  return member_field<P>(field_declaration(name, {"boolean"}, std::nullopt, "", std::move(help)),
                         access, std::nullopt, kStoreAs<bool>, kLoad);
}

template <typename P, typename Access>
Field<P> string(std::string name, Access access, std::string unit, std::string help) {
  return member_field<P>(
      field_declaration(name, {"string"}, std::nullopt, std::move(unit), std::move(help)), access,
      std::nullopt, kStoreAs<std::string>, kLoad);
}

// A string from a fixed set, stored as the enum value each name maps to.
template <typename P, typename Access>
Field<P> choice(std::string name, Access access,
                std::vector<std::pair<std::string, FieldRef<P, Access>>> names, std::string help) {
  using E = FieldRef<P, Access>;
  std::vector<std::string> choices;
  for (const auto& [text, e] : names) choices.push_back(text);
  return member_field<P>(
      field_declaration(name, {"string"}, std::nullopt, "", std::move(help), choices), access,
      std::nullopt,
      [names](E& slot, ParamValue v) {
        for (const auto& [text, e] : names)
          if (text == std::get<std::string>(v)) slot = e;
      },
      [names](const E& slot) -> std::optional<ParamValue> {
        for (const auto& [text, e] : names)
          if (e == slot) return text;
        return std::nullopt;
      });
}

// A field that must be given to the constructor (it has no default).
template <typename P>
Field<P> required(Field<P> f) {
  f.info.required = true;
  return f;
}

// A construction option, not part of the object's state (not in params(), describe, set{}).
template <typename P>
Field<P> option(Field<P> f) {
  f.info.state = false;
  return f;
}

// Sets field `name` of the table on top of the stack to a callable table: calling it calls
// `constructor` with the call's arguments; `.defaults` and `.fields` describe its keys.
void set_constructor(lua_State* L, const char* name, lua_CFunction constructor,
                     const std::vector<Declaration>& infos);

// Sets `invasim.<type>.<method>` to {defaults =, fields =}, describing the keyword table of a
// method (dyn:pressure_wall{}, sys:compress{}); the table on top of the stack is `invasim`,
// whose field `type` must already be a constructor table.
void set_method_keys(lua_State* L, const char* type, const char* method,
                     const std::vector<Declaration>& infos);

// Sets `invasim.<type>.<name>` to the function fn (invasim.Contacts.check); the table on top
// of the stack is `invasim`, whose field `type` must already be a constructor table.
void set_static_function(lua_State* L, const char* type, const char* name, lua_CFunction fn);

// The tables set_constructor and set_method_keys have published, by name ("Contacts",
// "Dynamics:pressure_wall"): for `invasim keys` and the documentation.
const std::map<std::string, std::vector<Declaration>>& registered_field_tables();

// The listing of a type's keys for documentation and `invasim fields`: one line per key (name,
// type, default or "required", range or choices, unit, help).
std::string format_field_table(const std::vector<Declaration>& infos);

}  // namespace invasim::lua
