#include "core/params.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <iterator>
#include <map>
#include <optional>
#include <sstream>

#include "core/errors.hpp"
#include "core/names.hpp"

namespace invasim {

const char* type_name(ParamType type) {
  static constexpr const char* kNames[] = {"number", "integer", "boolean", "string"};
  const auto k = static_cast<std::size_t>(type);
  return k < std::size(kNames) ? kNames[k] : "?";
}

std::string format_value(const ParamValue& value) {
  if (const auto* d = std::get_if<double>(&value)) {
    return format_number(*d);
  }
  if (const auto* i = std::get_if<long long>(&value)) return std::to_string(*i);
  if (const auto* b = std::get_if<bool>(&value)) return *b ? "true" : "false";
  return std::get<std::string>(value);
}

namespace {

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  const auto last = text.find_last_not_of(" \t");
  return text.substr(first, last - first + 1);
}

// Skips a leading '+' (from_chars takes none), but not in "+-5", which stays refused.
void skip_plus_sign(const char*& begin, const char* end) {
  if (begin != end && *begin == '+' && (begin + 1 == end || begin[1] != '-')) ++begin;
}

// Whole-string double parse (accepts a leading '+'); nullopt if anything is left over.
std::optional<double> parse_double(const std::string& text) {
  const char* begin = text.data();
  const char* end = begin + text.size();
  skip_plus_sign(begin, end);
  double value = 0.0;
  const auto result = std::from_chars(begin, end, value);
  if (result.ec != std::errc() || result.ptr != end || begin == end) return std::nullopt;
  return value;
}

// True if text is a number whose magnitude a double cannot hold (1e-400, 1e400).
bool beyond_double(const std::string& text) {
  const char* begin = text.data();
  const char* end = begin + text.size();
  skip_plus_sign(begin, end);
  double value = 0.0;
  const auto result = std::from_chars(begin, end, value);
  return result.ec == std::errc::result_out_of_range && result.ptr == end;
}

std::optional<long long> parse_integer(const std::string& text) {
  const char* begin = text.data();
  const char* end = begin + text.size();
  skip_plus_sign(begin, end);
  long long value = 0;
  const auto result = std::from_chars(begin, end, value);
  if (result.ec == std::errc() && result.ptr == end && begin != end) return value;
  // Integral floats such as "2e5" are integers too (as in Lua's math.tointeger).
  const auto d = parse_double(text);
  if (d && std::isfinite(*d) && std::floor(*d) == *d && std::fabs(*d) < 9.2e18)
    return static_cast<long long>(*d);
  return std::nullopt;
}

std::optional<bool> parse_boolean(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (text == "true" || text == "yes" || text == "on" || text == "1") return true;
  if (text == "false" || text == "no" || text == "off" || text == "0") return false;
  return std::nullopt;
}

}  // namespace

ParamValue parse_value(ParamType type, const std::string& key, const std::string& raw) {
  const std::string text = trim(raw);
  const auto fail = [&](const char* expected) -> ParamValue {
    fail_input("parameter '", key, "' is ", expected, "; cannot parse '", raw, "'");
  };
  switch (type) {
    case ParamType::kNumber: {
      const auto d = parse_double(text);
      if (!d && beyond_double(text))
        fail_input("parameter '", key, "' is a number; '", raw,
                   "' is beyond the range of a "
                   "double (magnitudes from about 5e-324 to 1.8e308, or 0)");
      // inf and -inf are numbers (a range with a closed infinite end takes them: tau_p's
      // [0, inf]); NaN is none.
      if (!d || std::isnan(*d)) return fail("a number");
      return *d == 0.0 ? 0.0 : *d;  // -0 is 0: the same parameters, run id and params.json
    }
    case ParamType::kInteger: {
      const auto i = parse_integer(text);
      if (!i) return fail("an integer");
      return *i;
    }
    case ParamType::kBoolean: {
      const auto b = parse_boolean(text);
      if (!b) return fail("a boolean (true/false, yes/no, on/off, 1/0)");
      return *b;
    }
    case ParamType::kString:
      return raw;
  }
  return raw;
}

Range parse_range(const std::string& key, const std::string& raw) {
  const std::string text = trim(raw);
  const auto fail = [&](const std::string& why) -> Range {
    fail_input("params: parameter '", key, "': range '", raw, "' ", why);
  };
  const std::string form =
      "is not in interval notation: write \"[lo, hi]\" with [ ] inclusive, ( ) exclusive and "
      "inf for no bound, e.g. \"(0, inf)\"";
  if (text.size() < 2) return fail(form);
  const char open = text.front(), close = text.back();
  const auto comma = text.find(',');
  if ((open != '[' && open != '(') || (close != ']' && close != ')') ||
      comma == std::string::npos || text.find(',', comma + 1) != std::string::npos)
    return fail(form);
  const auto lo = parse_double(trim(text.substr(1, comma - 1)));
  const auto hi = parse_double(trim(text.substr(comma + 1, text.size() - comma - 2)));
  if (!lo || !hi || std::isnan(*lo) || std::isnan(*hi)) return fail(form);
  Range range{*lo, *hi, open == '(', close == ')'};
  const bool empty =
      range.lo > range.hi ||
      (range.lo == range.hi && (range.lo_open || range.hi_open || std::isinf(range.lo)));
  if (empty) return fail("is empty: no value lies in it");
  return range;
}

namespace {

// Whether `value` satisfies p's range and choices (true if p has neither).
bool allowed(const Param& p, const ParamValue& value) {
  if (p.range) {
    if (const auto* d = std::get_if<double>(&value)) return p.range->contains(*d);
    if (const auto* i = std::get_if<long long>(&value))
      return p.range->contains(static_cast<double>(*i));
  }
  if (const auto* s = std::get_if<std::string>(&value); s && !p.choices.empty())
    return std::find(p.choices.begin(), p.choices.end(), *s) != p.choices.end();
  return true;
}

// "in (0, inf)" or "one of a, b".
std::string allowed_text(const Param& p) {
  return p.range ? "in " + p.range->notation() : "one of " + join_names(p.choices);
}

// A value as a message quotes it: strings in single quotes.
std::string quoted(const ParamValue& value) {
  return std::holds_alternative<std::string>(value) ? cat("'", format_value(value), "'")
                                                    : format_value(value);
}

}  // namespace

std::string value_violation(const Param& p, const ParamValue& value) {
  if (allowed(p, value)) return "";
  const auto* s = std::get_if<std::string>(&value);
  return cat("must be ", allowed_text(p), "; got ", quoted(value),
             s ? did_you_mean(*s, p.choices) : "");
}

std::string default_violation(const Param& p) {
  if (allowed(p, p.default_value)) return "";
  return cat("must be ", allowed_text(p), "; its default is ", quoted(p.default_value));
}

Override parse_override(const std::string& argument) {
  const auto eq = argument.find('=');
  if (eq == std::string::npos) fail_input("--set expects key=value, got '", argument, "'");
  const std::string key = trim(argument.substr(0, eq));
  if (key.empty()) fail_input("--set expects key=value, got '", argument, "' (no key)");
  return Override{key, argument.substr(eq + 1), false};
}

namespace {

std::string describe(const Override& o) {
  return o.from_seed_flag ? "--seed " + o.text : "--set " + o.key + "=" + o.text;
}

}  // namespace

void apply_overrides(std::vector<Param>& params, const std::vector<Override>& overrides) {
  std::vector<std::string> declared;
  for (const auto& p : params) declared.push_back(p.name);
  std::map<std::string, const Override*> seen;
  for (const auto& o : overrides) {
    auto it =
        std::find_if(params.begin(), params.end(), [&](const Param& p) { return p.name == o.key; });
    if (it == params.end()) {
      const std::string listing = declared.empty() ? "the protocol declares no parameters"
                                                   : "declared parameters: " + join_names(declared);
      if (o.from_seed_flag)
        fail_input("--seed: the protocol declares no parameter 'seed'; ", listing);
      fail_input(describe(o), ": '", o.key, "' is not a parameter of this protocol",
                 did_you_mean(o.key, declared), "; ", listing);
    }
    if (const auto [previous, inserted] = seen.emplace(o.key, &o); !inserted)
      fail_input("parameter '", o.key, "' is set twice on the command line (",
                 describe(*previous->second), " and ", describe(o), ")");
    try {
      it->value = parse_value(it->type, it->name, o.text);
    } catch (const InputError& e) {
      // A number an integer parameter cannot take: a fraction, or beyond 64 bits.
      const auto number =
          it->type == ParamType::kInteger ? parse_double(trim(o.text)) : std::nullopt;
      std::string hint;
      if (number && std::isfinite(*number) && std::floor(*number) != *number)
        hint =
            cat(" (to accept fractions, write its default with a decimal point in the "
                "protocol: ",
                format_value(it->default_value), ".0)");
      else if (number && !std::isnan(*number))
        hint = " (beyond the 64-bit integers, whose magnitude is at most 9223372036854775807)";
      fail_input(describe(o), ": ", e.what(), hint);
    }
    if (const std::string why = value_violation(*it, it->value); !why.empty())
      fail_input(describe(o), ": parameter '", it->name, "' ", why);
    it->overridden = true;
  }
}

std::string format_param_table(const std::vector<Param>& params) {
  if (params.empty()) return "  (no parameters)\n";
  const bool any_overridden =
      std::any_of(params.begin(), params.end(), [](const Param& p) { return p.overridden; });
  const bool any_range = std::any_of(params.begin(), params.end(),
                                     [](const Param& p) { return p.range || !p.choices.empty(); });
  const auto shown = [](const Param& p, const ParamValue& v) {
    return p.type == ParamType::kString ? cat('"', format_value(v), '"') : format_value(v);
  };
  // "(0, inf)" for a range, "{a, b}" for choices, "-" for neither.
  const auto allowed_cell = [](const Param& p) {
    if (p.range) return p.range->notation();
    if (!p.choices.empty()) return cat("{", join_names(p.choices), "}");
    return std::string("-");
  };
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> header = {"name", "type", "default"};
  if (any_overridden) header.push_back("value");
  if (any_range) header.push_back("range");
  header.insert(header.end(), {"unit", "meaning"});
  rows.push_back(header);
  for (const auto& p : params) {
    std::vector<std::string> row = {p.name, type_name(p.type), shown(p, p.default_value)};
    if (any_overridden) row.push_back(p.overridden ? shown(p, p.value) : "");
    if (any_range) row.push_back(allowed_cell(p));
    row.insert(row.end(), {p.unit.empty() ? "-" : p.unit, p.help});
    rows.push_back(row);
  }
  return aligned_table(rows);
}

}  // namespace invasim
