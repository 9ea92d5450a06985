#pragma once
// The one form that declares a protocol parameter (invasim.params) and a stage keyword
// (invasim.keywords): a bare default (`seed = 1`, `label = "stage"`) or a table
//
//   {default, type = "number", range = "(0, inf)", choices = {"a", "b"}, unit = "tau",
//    help = "time step", required = true}
//
// whose first entry is the default. The type follows the default (a Lua integer: "integer",
// a float: "number", a string, a boolean) unless `type` names it. A parameter has a default and
// one of the four plain types; a keyword may also be required (no default), optional (neither),
// of type "function", "table", "userdata", "any", a bound type name ("Ramp", "Group") or
// alternatives joined by '|' ("number|Ramp"). `range` applies to numbers and integers,
// `choices` to strings, and a plain default must lie inside them.
#include <cmath>
#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

#include "core/params.hpp"

struct lua_State;

namespace invasim::lua {

enum class DeclarationUse { kParameter, kKeyword };

// How a declaration is written, for the messages that refuse one.
inline constexpr const char* kDeclarationForm =
    "write name = default or name = {default, unit = ..., help = ...}";

// One declared key: a protocol parameter, a stage keyword, or a key of an engine type's keyword
// table (a Field of lua/fields.hpp, whose default is the engine struct's own).
struct Declaration {
  std::string name;
  std::vector<std::string> types;           // alternatives; empty: any value
  std::optional<ParamValue> default_value;  // a default of a plain type
  bool has_default = false;                 // any default, a table's included
  std::optional<Range> range;
  std::vector<std::string> choices;
  std::string unit;
  std::string help;
  bool required = false;
  // Engine fields only: part of the object's state (params(), describe, set{}) rather than a
  // construction option such as `group`; and the list form shown instead of the type ("list
  // of 3 numbers").
  bool state = true;
  std::string list_form;

  // As a protocol parameter (for a kParameter declaration: one plain type and a default).
  Param to_param() const;
  // The type as listings and messages show it: "number", "number or Ramp", "list of 3 numbers".
  std::string type_text() const;
};

// A declaration from its parts (an engine field's, a typed getter's): types, range, unit, help,
// choices.
inline Declaration field_declaration(std::string name, std::vector<std::string> types,
                                     std::optional<Range> range, std::string unit, std::string help,
                                     std::vector<std::string> choices = {}) {
  Declaration d;
  d.name = std::move(name);
  d.types = std::move(types);
  d.range = std::move(range);
  d.choices = std::move(choices);
  d.unit = std::move(unit);
  d.help = std::move(help);
  return d;
}

// A key a binding reads itself (an object, a function, a table), not a field of the object's
// state: declared for the listings (invasim keys, .fields) with no default.
inline Declaration option_key(std::string name, std::string type, std::string help) {
  Declaration d =
      field_declaration(std::move(name), {std::move(type)}, std::nullopt, "-", std::move(help));
  d.state = false;
  return d;
}

// The declarations of a field table followed by those of the keys its binding reads itself.
inline std::vector<Declaration> with_options(std::vector<Declaration> fields,
                                             std::initializer_list<Declaration> options) {
  fields.insert(fields.end(), options.begin(), options.end());
  return fields;
}

// A number range as declarations state it: a key that takes finite values only has an open
// upper end at inf ("[0, inf)"), one that also takes math.huge a closed one ("[0, inf]").
inline Range shown_range(Range range, bool allow_infinity) {
  if (std::isinf(range.hi) && range.hi > 0) range.hi_open = !allow_infinity;
  return range;
}

// Reads the declaration of `name` at `index`. `owner` prefixes every message ("params:
// parameter 'dt'"). A default that is not plain (a table) stays in the entry: entry[1].
Declaration read_declaration(lua_State* L, int index, const std::string& owner,
                             const std::string& name, DeclarationUse use);

// "a number", "an integer", "an invasim.ramp{}"; alternatives joined by "or".
std::string expected_text(const std::vector<std::string>& types);

}  // namespace invasim::lua
