#include "sweep/python_json.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <vector>

#include "core/errors.hpp"
#include "io/json.hpp"
#include "sweep/md5.hpp"

namespace invasim::sweep {

std::string python_float_repr(double value) {
  if (std::isnan(value)) return "NaN";
  if (std::isinf(value)) return value > 0 ? "Infinity" : "-Infinity";
  // Shortest round-trip digits in scientific form: [-]d[.ddd]e[+-]XX.
  char buffer[64];
  const auto result =
      std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::scientific);
  const std::string text(buffer, result.ptr);
  const bool negative = text[0] == '-';
  const auto e = text.find('e');
  std::string digits;
  for (std::size_t i = negative ? 1 : 0; i < e; ++i)
    if (text[i] != '.') digits += text[i];
  const int exponent = std::stoi(text.substr(e + 1));
  const int decpt = exponent + 1;  // value = 0.DIGITS x 10^decpt, as in Python's dtoa
  const int n = static_cast<int>(digits.size());
  std::string out = negative ? "-" : "";
  if (decpt <= -4 || decpt > 16) {
    out += digits[0];
    if (n > 1) {
      out += '.';
      out.append(digits, 1);
    }
    char exp_text[16];
    std::snprintf(exp_text, sizeof exp_text, "e%c%02d", exponent < 0 ? '-' : '+',
                  std::abs(exponent));
    return out + exp_text;
  }
  if (decpt <= 0) {
    out += "0.";
    out.append(static_cast<std::size_t>(-decpt), '0');
    out += digits;
  } else if (decpt < n) {
    out.append(digits, 0, decpt);
    out += '.';
    out.append(digits, decpt);
  } else {
    out += digits;
    out.append(static_cast<std::size_t>(decpt - n), '0');
    out += ".0";
  }
  return out;
}

namespace {

// The code points of a UTF-8 string; InputError on malformed bytes.
std::vector<char32_t> code_points(std::string_view text) {
  std::vector<char32_t> out;
  for (std::size_t i = 0; i < text.size();) {
    const auto byte = static_cast<unsigned char>(text[i]);
    const int extra = byte < 0x80         ? 0
                      : (byte >> 5) == 6  ? 1
                      : (byte >> 4) == 14 ? 2
                      : (byte >> 3) == 30 ? 3
                                          : -1;
    if (extra < 0 || i + static_cast<std::size_t>(extra) >= text.size())
      fail_input("state point text '", text, "' is not valid UTF-8");
    char32_t c = extra == 0 ? byte : byte & (0x3f >> extra);
    for (int k = 1; k <= extra; ++k) {
      const auto next = static_cast<unsigned char>(text[i + k]);
      if ((next >> 6) != 2) fail_input("state point text '", text, "' is not valid UTF-8");
      c = (c << 6) | (next & 0x3f);
    }
    out.push_back(c);
    i += extra + 1;
  }
  return out;
}

void append_escaped(std::string& out, std::string_view text) {
  static const char* const hex = "0123456789abcdef";
  const auto unit = [&](unsigned u) {
    out += "\\u";
    for (int shift = 12; shift >= 0; shift -= 4) out += hex[(u >> shift) & 15];
  };
  out += '"';
  for (const char32_t c : code_points(text)) {
    switch (c) {
      case '"':
        out += "\\\"";
        continue;
      case '\\':
        out += "\\\\";
        continue;
      case '\n':
        out += "\\n";
        continue;
      case '\r':
        out += "\\r";
        continue;
      case '\t':
        out += "\\t";
        continue;
      case '\b':
        out += "\\b";
        continue;
      case '\f':
        out += "\\f";
        continue;
      default:
        break;
    }
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else if (c < 0x10000) {
      unit(static_cast<unsigned>(c));
    } else {
      const unsigned v = static_cast<unsigned>(c) - 0x10000;
      unit(0xd800 + (v >> 10));
      unit(0xdc00 + (v & 0x3ff));
    }
  }
  out += '"';
}

}  // namespace

std::string python_dumps(const Json& value) {
  // io/json's writer on one line (separators ", " and ": ", keys in byte order, which is
  // Python's code-point order) with Python's floats and ensure_ascii strings.
  std::string out;
  append_json(out, value, 0, 0, JsonStyle{&python_float_repr, &append_escaped});
  return out;
}

std::string signac_id(const Json& statepoint) {
  return md5_hex(python_dumps(statepoint));
}

}  // namespace invasim::sweep
