#pragma once
// Protocol parameters, independent of Lua: a declared parameter has a type (inferred from its
// default), a unit, a one-line meaning and optionally its allowed values (a range in interval
// notation for numbers, a list of choices for strings); command-line overrides (--set
// key=value) are parsed to the declared type and checked against them. All failures are
// InputErrors that name the key and the value.
#include <limits>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "core/range.hpp"

namespace invasim {

enum class ParamType { kNumber, kInteger, kBoolean, kString };

using ParamValue = std::variant<double, long long, bool, std::string>;

// One declared parameter; `value` is the default unless an override replaced it. `range`
// (numbers, integers) and `choices` (strings) restrict the values, defaults included.
struct Param {
  std::string name;
  ParamType type = ParamType::kNumber;
  ParamValue default_value;
  ParamValue value;
  std::string unit;
  std::string help;
  bool overridden = false;
  std::optional<Range> range;  // written in interval notation: "[0, 1)", "(0, inf)"
  std::vector<std::string> choices;
};

// A command-line `--set key=value` (or `--seed S`, with from_seed_flag set).
struct Override {
  std::string key;
  std::string text;
  bool from_seed_flag = false;
};

const char* type_name(ParamType type);

// "number", "integer", ... value formatted the way `--set` would accept it back.
std::string format_value(const ParamValue& value);

// Parses `text` as a value of `type` for parameter `key`; throws InputError naming both.
// Integers accept integral floats ("2e5"); booleans accept true/false, yes/no, on/off, 1/0.
ParamValue parse_value(ParamType type, const std::string& key, const std::string& text);

// Parses the `range = "..."` of parameter `key`'s declaration: two bounds (numbers, inf or
// -inf) between '[' or '(' and ']' or ')'. Throws InputError naming the parameter and the text
// if it is malformed, has a NaN bound or is empty.
Range parse_range(const std::string& key, const std::string& text);

// Why `value` is not allowed for `p` ("must be in (0, inf); got 0", "must be one of a, b; got
// 'c'"), or "" if it is allowed (or p has no range or choices).
std::string value_violation(const Param& p, const ParamValue& value);

// Why p's default is not allowed ("must be in (0, inf); its default is 0"), or "".
std::string default_violation(const Param& p);

// Splits "key=value" from the command line; throws InputError if there is no '=' or no key.
Override parse_override(const std::string& argument);

// Applies overrides to declared parameters. An undeclared key is an error listing the
// declared ones; a key given twice is an error; a value outside the parameter's range or
// choices is an error naming the override ("--set dt=0: parameter 'dt' must be in (0, inf);
// got 0").
void apply_overrides(std::vector<Param>& params, const std::vector<Override>& overrides);

// The `invasim params` listing: one line per parameter (name, type, default, the --set value
// if any, the range or choices if any parameter has one, unit, help).
std::string format_param_table(const std::vector<Param>& params);

}  // namespace invasim
