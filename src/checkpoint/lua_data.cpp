#include "checkpoint/lua_data.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "io/io_error.hpp"

namespace invasim {

namespace {

bool is_digit(char c) {
  return c >= '0' && c <= '9';
}
bool is_hex(char c) {
  return is_digit(c) || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F');
}
int hex_value(char c) {
  return is_digit(c) ? c - '0' : (c | 0x20) - 'a' + 10;
}
bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
}

// Recursive descent over the text; depth bounded by kMaxLuaDataDepth.
class Parser {
 public:
  Parser(std::string_view text, const std::string& origin) : s_(text), origin_(origin) {}

  LuaDatum document() {
    LuaDatum v = value(0);
    skip_space();
    if (at_ < s_.size()) fail("unexpected text after the value");
    return v;
  }

 private:
  template <typename... Parts>
  [[noreturn]] void fail(const Parts&... parts) const {
    const std::size_t at = std::min(at_, s_.size());
    const auto line = 1 + std::count(s_.begin(), s_.begin() + std::ptrdiff_t(at), '\n');
    fail_io(origin_, ": line ", line, " (offset ", at, "): ", parts...,
            " (expected plain Lua data: nil, true, false, numbers, strings, tables)");
  }

  void skip_space() {
    while (at_ < s_.size() && is_space(s_[at_])) ++at_;
  }
  bool accept(std::string_view word) {
    if (s_.substr(at_, word.size()) != word) return false;
    at_ += word.size();
    return true;
  }
  char peek() const { return at_ < s_.size() ? s_[at_] : '\0'; }

  LuaDatum value(int depth) {
    skip_space();
    LuaDatum v;
    if (at_ >= s_.size()) fail("the text ends where a value should be");
    const char c = s_[at_];
    if (c == '{') return table(depth + 1);
    if (c == '"' || c == '\'') {
      v.kind = LuaDatum::Kind::kString;
      v.string = string();
      return v;
    }
    if (c == '-') {
      ++at_;
      skip_space();
      v = number();
      if (v.kind == LuaDatum::Kind::kInteger)
        v.integer = std::int64_t(std::uint64_t(0) - std::uint64_t(v.integer));  // wraps as Lua
      else
        v.number = -v.number;
      return v;
    }
    if (is_digit(c) || c == '.' || s_.substr(at_, 4) == "math" || s_.substr(at_, 3) == "0/0")
      return number();
    if (accept("nil")) return v;
    if (accept("true") || accept("false")) {
      v.kind = LuaDatum::Kind::kBoolean;
      v.boolean = s_[at_ - 1] == 'e' && s_[at_ - 2] == 'u';  // "true", not "false"
      return v;
    }
    fail("unexpected character '", c, "'");
  }

  LuaDatum table(int depth) {
    if (depth > kMaxLuaDataDepth) fail("tables nested deeper than ", kMaxLuaDataDepth, " levels");
    ++at_;  // '{'
    LuaDatum t;
    t.kind = LuaDatum::Kind::kTable;
    for (;;) {
      skip_space();
      if (peek() == '}') {
        ++at_;
        return t;
      }
      if (peek() != '[') fail("a table entry must be [key]=value");
      ++at_;
      LuaDatum key = value(depth);
      if (key.kind == LuaDatum::Kind::kNil) fail("a table key is nil");
      if (key.kind == LuaDatum::Kind::kNumber && std::isnan(key.number)) fail("a table key is NaN");
      skip_space();
      if (peek() != ']') fail("']' expected after a table key");
      ++at_;
      skip_space();
      if (peek() != '=') fail("'=' expected after [key]");
      ++at_;
      LuaDatum val = value(depth);
      t.entries.emplace_back(std::move(key), std::move(val));
      skip_space();
      if (peek() == ',' || peek() == ';')
        ++at_;
      else if (peek() != '}')
        fail("',' or '}' expected in a table");
    }
  }

  // A numeral, 0/0 (NaN as Lua computes it) or math.huge; no sign.
  LuaDatum number() {
    LuaDatum v;
    v.kind = LuaDatum::Kind::kNumber;
    if (accept("math.huge")) {
      v.number = std::numeric_limits<double>::infinity();
      return v;
    }
    if (accept("0/0")) {
      volatile double zero = 0.0;  // computed at run time, as Lua does (the same NaN bits)
      v.number = zero / zero;
      return v;
    }
    const std::size_t start = at_;
    const bool hex = s_.substr(at_, 2) == "0x" || s_.substr(at_, 2) == "0X";
    if (hex) at_ += 2;
    bool fraction = false;
    auto digits = [&] {
      while (at_ < s_.size() && (hex ? is_hex(s_[at_]) : is_digit(s_[at_]))) ++at_;
    };
    digits();
    if (peek() == '.') {
      fraction = true;
      ++at_;
      digits();
    }
    if (peek() == (hex ? 'p' : 'e') || peek() == (hex ? 'P' : 'E')) {
      fraction = true;
      ++at_;
      if (peek() == '+' || peek() == '-') ++at_;
      if (!is_digit(peek())) fail("malformed number");
      while (is_digit(peek())) ++at_;
    }
    const std::string text(s_.substr(start, at_ - start));
    if (text.empty() || text == "." || text == "0x" || text == "0X" || text == "0x." ||
        text == "0X." ||
        (at_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[at_])) || s_[at_] == '_')))
      fail("malformed number '", s_.substr(start, std::min<std::size_t>(at_ - start + 1, 40)), "'");
    if (!fraction) {  // an integer numeral
      std::uint64_t a = 0;
      bool overflow = false;
      for (std::size_t k = hex ? 2 : 0; k < text.size(); ++k) {
        const unsigned d = unsigned(hex_value(text[k]));
        if (hex) {
          a = a * 16 + d;  // hexadecimal integers wrap around (Lua 5.4)
        } else if (a > (std::uint64_t(std::numeric_limits<std::int64_t>::max()) - d) / 10) {
          overflow = true;  // a decimal integer that does not fit is a float
          break;
        } else {
          a = a * 10 + d;
        }
      }
      if (!overflow) {
        v.kind = LuaDatum::Kind::kInteger;
        v.integer = std::int64_t(a);
        return v;
      }
    }
    v.number = std::strtod(text.c_str(), nullptr);
    return v;
  }

  // A short string in double or single quotes with Lua's escapes.
  std::string string() {
    const char quote = s_[at_++];
    std::string out;
    for (;;) {
      if (at_ >= s_.size()) fail("unfinished string");
      const char c = s_[at_++];
      if (c == quote) return out;
      if (c == '\n' || c == '\r') fail("unfinished string (a line break inside it)");
      if (c != '\\') {
        out += c;
        continue;
      }
      if (at_ >= s_.size()) fail("unfinished string");
      const char e = s_[at_++];
      switch (e) {
        case 'a':
          out += '\a';
          break;
        case 'b':
          out += '\b';
          break;
        case 'f':
          out += '\f';
          break;
        case 'n':
          out += '\n';
          break;
        case 'r':
          out += '\r';
          break;
        case 't':
          out += '\t';
          break;
        case 'v':
          out += '\v';
          break;
        case '\\':
          out += '\\';
          break;
        case '"':
          out += '"';
          break;
        case '\'':
          out += '\'';
          break;
        case '\n':
        case '\r':  // an escaped line break ("\r\n" and "\n\r" count once)
          out += '\n';
          if (at_ < s_.size() && (s_[at_] == '\n' || s_[at_] == '\r') && s_[at_] != e) ++at_;
          break;
        case 'x': {
          if (at_ + 2 > s_.size() || !is_hex(s_[at_]) || !is_hex(s_[at_ + 1]))
            fail("\\x needs two hexadecimal digits");
          out += char(hex_value(s_[at_]) * 16 + hex_value(s_[at_ + 1]));
          at_ += 2;
          break;
        }
        case 'z':
          skip_space();
          break;
        default: {
          if (!is_digit(e)) fail("invalid escape '\\", e, "' in a string");
          int code = e - '0';
          for (int k = 0; k < 2 && is_digit(peek()); ++k) code = code * 10 + (s_[at_++] - '0');
          if (code > 255) fail("escape '\\", code, "' is larger than 255");
          out += char(code);
        }
      }
    }
  }

  std::string_view s_;
  const std::string& origin_;
  std::size_t at_ = 0;
};

}  // namespace

LuaDatum parse_lua_data(std::string_view text, const std::string& origin) {
  return Parser(text, origin).document();
}

}  // namespace invasim
