#include "core/range.hpp"

#include <charconv>
#include <cmath>

namespace invasim {

std::string format_number(double x) {
  if (std::isnan(x)) return "nan";  // whatever its sign bit (to_chars writes "-nan")
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, x);  // shortest round trip
  return std::string(buffer, result.ptr);
}

bool Range::contains(double x) const {
  const bool above = lo_open ? x > lo : x >= lo;
  const bool below = hi_open ? x < hi : x <= hi;
  return above && below;
}

std::string Range::describe() const {
  const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
  if (has_lo && has_hi)
    return std::string("in ") + (lo_open ? "(" : "[") + format_number(lo) + ", " +
           format_number(hi) + (hi_open ? ")" : "]");
  if (has_lo) return (lo_open ? "> " : ">= ") + format_number(lo);
  if (has_hi) return (hi_open ? "< " : "<= ") + format_number(hi);
  return "finite";
}

std::string Range::notation() const {
  const auto bound = [](double b) {
    return std::isinf(b) ? std::string(b < 0 ? "-inf" : "inf") : format_number(b);
  };
  std::string text(lo_open ? "(" : "[");  // appended, not operator+ (GCC 12 -Wrestrict)
  text += bound(lo);
  text += ", ";
  text += bound(hi);
  text += hi_open ? ")" : "]";
  return text;
}

}  // namespace invasim
