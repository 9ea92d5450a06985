#pragma once
// Protocol parameters, independent of Lua: a declared parameter has a type (inferred from its
// default), a unit and a one-line meaning; command-line overrides (--set key=value) are parsed
// to the declared type. All failures are InputErrors that name the key and the value.
#include <string>
#include <variant>
#include <vector>

namespace invasim::lua {

enum class ParamType { kNumber, kInteger, kBoolean, kString };

using ParamValue = std::variant<double, long long, bool, std::string>;

// One declared parameter; `value` is the default unless an override replaced it.
struct Param {
  std::string name;
  ParamType type = ParamType::kNumber;
  ParamValue default_value;
  ParamValue value;
  std::string unit;
  std::string help;
  bool overridden = false;
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

// Splits "key=value" from the command line; throws InputError if there is no '=' or no key.
Override parse_override(const std::string& argument);

// Applies overrides to declared parameters. An undeclared key is an error listing the
// declared ones; a key given twice is an error.
void apply_overrides(std::vector<Param>& params, const std::vector<Override>& overrides);

// The `invasim params` listing: one line per parameter (name, type, default, unit, help).
std::string format_param_table(const std::vector<Param>& params);

}  // namespace invasim::lua
