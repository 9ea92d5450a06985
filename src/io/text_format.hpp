#pragma once
// Locale-independent number formatting and parsing for the text formats (XYZ, VTK XML, SVG).
// Doubles are written in their shortest round-trip form (std::to_chars), so a text snapshot
// read back gives the exact same doubles; parsing uses std::from_chars (no locale surprises).
#include <charconv>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace invasim::text {

// Appends the shortest decimal form of v that parses back to exactly v.
inline void append(std::string& out, double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, std::size_t(r.ptr - buf));
}
inline void append(std::string& out, std::int64_t v) {
  char buf[24];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, std::size_t(r.ptr - buf));
}
inline void append(std::string& out, int v) {
  append(out, std::int64_t(v));
}
inline void append(std::string& out, std::uint64_t v) {
  char buf[24];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, std::size_t(r.ptr - buf));
}
// Appends a double with a fixed number of decimals (SVG coordinates).
inline void append_fixed(std::string& out, double v, int decimals) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, decimals);
  out.append(buf, std::size_t(r.ptr - buf));
}

// Appends " x y z" (the rows of the XYZ and VTK formats); v is any 3-vector.
template <typename V>
void append_xyz(std::string& out, const V& v) {
  for (int a = 0; a < 3; ++a) append(out += ' ', double(v[a]));
}

// "(x, y, z)", for messages.
template <typename V>
std::string vec_text(const V& v) {
  std::string t = "(";
  for (int a = 0; a < 3; ++a) append(t += a ? ", " : "", double(v[a]));
  return t + ")";
}

// Parses a whole token as a number; nullopt if it is not exactly one number.
template <typename T>
std::optional<T> parse(std::string_view token) {
  T value{};
  const char* end = token.data() + token.size();
  const auto r = std::from_chars(token.data(), end, value);
  if (r.ec != std::errc() || r.ptr != end) return std::nullopt;
  return value;
}

// Splits on ASCII whitespace, skipping empty tokens.
inline void split_whitespace(std::string_view s, std::vector<std::string_view>& out) {
  out.clear();
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t' || s[i] == '\n' || s[i] == '\r')) ++i;
    const std::size_t start = i;
    while (i < s.size() && !(s[i] == ' ' || s[i] == '\t' || s[i] == '\n' || s[i] == '\r')) ++i;
    if (i > start) out.push_back(s.substr(start, i - start));
  }
}

}  // namespace invasim::text
