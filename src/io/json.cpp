#include "io/json.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "io/atomic_file.hpp"
#include "io/io_error.hpp"

namespace invasim {

std::string json_float(double v) {
  if (!std::isfinite(v)) return "null";
  char text[32];
  for (int digits = 15; digits <= 17; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, v);
    if (digits == 17 || std::strtod(text, nullptr) == v) break;
  }
  return text;
}

void append_json_string(std::string& out, std::string_view s) {
  out += '"';
  for (char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\t') {
      out += "\\t";
    } else if (c == '\r') {
      out += "\\r";
    } else if (u < 0x20 || u == 0x7f) {
      char code[8];
      std::snprintf(code, sizeof code, "\\u%04x", unsigned(u));
      out += code;
    } else {
      out += c;
    }
  }
  out += '"';
}

void append_json(std::string& out, const Json& value, int indent, int level,
                 const JsonStyle& style) {
  switch (value.type()) {
    case Json::value_t::null:
      out += "null";
      return;
    case Json::value_t::boolean:
      out += value.get<bool>() ? "true" : "false";
      return;
    case Json::value_t::number_integer:
      out += std::to_string(value.get<std::int64_t>());
      return;
    case Json::value_t::number_unsigned:
      out += std::to_string(value.get<std::uint64_t>());
      return;
    case Json::value_t::number_float:
      out += style.number(value.get<double>());
      return;
    case Json::value_t::string:
      style.string(out, value.get_ref<const std::string&>());
      return;
    case Json::value_t::array: {
      out += '[';
      bool first = true;
      for (const Json& x : value) {
        if (!first) out += ", ";
        first = false;
        append_json(out, x, indent, level + 1, style);
      }
      out += ']';
      return;
    }
    case Json::value_t::object: {
      if (value.empty()) {
        out += "{}";
        return;
      }
      auto new_line = [&](int depth) {
        if (indent == 0) return;
        out += '\n';
        out.append(std::size_t(depth * indent), ' ');
      };
      out += '{';
      bool first = true;
      for (const auto& [key, x] : value.items()) {
        if (!first) out += indent > 0 ? "," : ", ";
        first = false;
        new_line(level + 1);
        style.string(out, key);
        out += ": ";
        append_json(out, x, indent, level + 1, style);
      }
      new_line(level);
      out += '}';
      return;
    }
    case Json::value_t::binary:
    case Json::value_t::discarded:
      break;
  }
  throw InputError("json_dump: a binary or discarded JSON value has no text form");
}

std::string json_dump(const Json& value, int indent) {
  if (indent < 0) fail_input("json_dump: indent = ", indent, " must be >= 0");
  std::string out;
  append_json(out, value, indent);
  out += '\n';
  return out;
}

Json parse_json(std::string_view text, const std::string& origin) {
  try {
    return Json::parse(text.begin(), text.end());
  } catch (const Json::parse_error& e) {
    // e.what() is "[json.exception.parse_error.101] parse error at line 2, column 5: ...".
    std::string_view what = e.what();
    if (const auto k = what.find("] "); k != std::string_view::npos) what.remove_prefix(k + 2);
    fail_io(origin, ": malformed JSON: ", what);
  }
}

Json read_json(const std::filesystem::path& path) {
  return parse_json(read_file(path), quoted(path));
}

}  // namespace invasim
