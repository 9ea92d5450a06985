#pragma once
// JSON documents (params.json, summary.json, sweep tables): the value type is nlohmann::json
// (Debian's nlohmann-json3-dev), whose objects keep their keys sorted; json_dump writes it in
// invasim's own layout, parse_json / read_json read any JSON text with errors naming the file.
//
// The layout of json_dump (that of every JSON file invasim writes):
// - objects: `{`, then one `"key": value` per line indented by `indent` spaces per level, keys
//   sorted bytewise, then `}` on its own line at the object's own indentation; `{}` if empty.
// - arrays: on one line, elements separated by ", "; `[]` if empty.
// - integers (signed or unsigned): as integers.
// - floats: the first of printf's %.15g, %.16g, %.17g that reads back to the same double.
//   Its digits are the shortest that round-trip (the digits of Python's repr); its layout is
//   %g's at that precision: no ".0" on integral values (1.0 -> 1), exponent form below 1e-4
//   (1e-05) and from 10^15 on (1e+15; 10^16 or 10^17 when 16 or 17 digits are needed).
//   NaN and infinities become null.
// - strings: `"` and `\` escaped, control characters as \n, \t, \r or \u00XX; other bytes
//   (UTF-8 included) as they are.
// - indent = 0 puts everything on one line: {"a": 1, "b": [1, 2]}.
// Reading back what json_dump wrote gives the same values (integral floats come back as
// integers, equal in value; -0.0, written -0, as the integer 0), and json_dump of that gives
// the same text.
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <string_view>

namespace invasim {

using Json = nlohmann::json;

// The float rule above, for one number (finite or not: "null").
std::string json_float(double v);

// `value` as JSON text in the layout above, ending in a newline.
std::string json_dump(const Json& value, int indent = 2);

// Refuses (InputError naming the string and the byte) a string that is not well-formed UTF-8.
void require_utf8(std::string_view s);
// Appends s as a JSON string with the escaping above; refuses s if it is not UTF-8.
void append_json_string(std::string& out, std::string_view s);

// How append_json writes floats and strings: invasim's rules above by default; the sweeps'
// Python json.dumps text (signac ids, sweep/python_json) swaps in Python's.
struct JsonStyle {
  std::string (*number)(double) = &json_float;
  void (*string)(std::string&, std::string_view) = &append_json_string;
};

// Appends `value` without the final newline; `level` is the nesting depth of `value`.
void append_json(std::string& out, const Json& value, int indent, int level = 0,
                 const JsonStyle& style = {});

// Parses JSON text; `origin` names it in messages. Throws IoError "<origin>: malformed JSON:
// ... at line L, column C: ...".
Json parse_json(std::string_view text, const std::string& origin);

// Reads and parses a JSON file; errors name the file.
Json read_json(const std::filesystem::path& path);

}  // namespace invasim
