#include "io/json.hpp"

#include <algorithm>
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

namespace {

// The length of the well-formed UTF-8 sequence at s[i] (RFC 3629: no overlong forms, no
// surrogates, at most U+10FFFF), or 0 if there is none.
std::size_t utf8_sequence(std::string_view s, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned lead = byte(i);
  if (lead < 0x80) return 1;
  std::size_t n = 0;
  unsigned lo = 0x80, hi = 0xbf;  // the range of the byte after the lead
  if (lead >= 0xc2 && lead <= 0xdf)
    n = 2;
  else if (lead >= 0xe0 && lead <= 0xef) {
    n = 3;
    if (lead == 0xe0) lo = 0xa0;
    if (lead == 0xed) hi = 0x9f;
  } else if (lead >= 0xf0 && lead <= 0xf4) {
    n = 4;
    if (lead == 0xf0) lo = 0x90;
    if (lead == 0xf4) hi = 0x8f;
  } else
    return 0;
  if (i + n > s.size() || byte(i + 1) < lo || byte(i + 1) > hi) return 0;
  for (std::size_t k = 2; k < n; ++k)
    if (byte(i + k) < 0x80 || byte(i + k) > 0xbf) return 0;
  return n;
}

}  // namespace

void require_utf8(std::string_view s) {
  for (std::size_t i = 0; i < s.size();) {
    const std::size_t n = utf8_sequence(s, i);
    if (n == 0) {
      char code[8];
      std::snprintf(code, sizeof code, "0x%02x", unsigned(static_cast<unsigned char>(s[i])));
      std::string shown(s.substr(0, std::min<std::size_t>(s.size(), 60)));
      for (char& c : shown)
        if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) c = '?';
      fail_input("JSON: the string '", shown, "' is not UTF-8 (byte ", code, " at position ", i + 1,
                 "): JSON text holds UTF-8 only, and a reader would refuse the file");
    }
    i += n;
  }
}

void append_json_string(std::string& out, std::string_view s) {
  require_utf8(s);
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
  } catch (const Json::exception& e) {
    // e.what() is "[json.exception.parse_error.101] parse error at line 2, column 5: ..."
    // (or out_of_range.406 "number overflow parsing '1e999'").
    std::string_view what = e.what();
    if (const auto k = what.find("] "); k != std::string_view::npos) what.remove_prefix(k + 2);
    fail_io(origin, ": malformed JSON: ", what);
  }
}

Json read_json(const std::filesystem::path& path) {
  return parse_json(read_file(path), quoted(path));
}

}  // namespace invasim
