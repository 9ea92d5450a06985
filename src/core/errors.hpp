#pragma once
// Error types. InputError: the user asked for something invalid (bad parameter, malformed
// mesh, site outside the walls); the message names the offending key or value.
// SimulationError: a running simulation became invalid (NaN, escaped site).
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace invasim {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class SimulationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A message as it can be shown: control characters other than newline and tab, which a
// quoted value from the user may hold, written as \xNN (a NUL byte would end the message
// where it is read as a C string, an escape sequence would act on the terminal).
inline std::string printable_message(const std::string& text) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if ((byte < 0x20 && c != '\n' && c != '\t') || byte == 0x7f) {
      out += "\\x";
      out += kHex[byte >> 4];
      out += kHex[byte & 15];
    } else {
      out += c;
    }
  }
  return out;
}

// Builds a message from streamable parts: fail_input("dt = ", dt, " must be > 0").
template <typename... Parts>
[[noreturn]] void fail_input(const Parts&... parts) {
  std::ostringstream out;
  (out << ... << parts);
  throw InputError(printable_message(out.str()));
}

template <typename... Parts>
[[noreturn]] void fail_simulation(const Parts&... parts) {
  std::ostringstream out;
  (out << ... << parts);
  throw SimulationError(printable_message(out.str()));
}

// Checks a scalar parameter and names it in the error. Every caller's parameter is a finite
// physical quantity: NaN (written "nan", whatever its sign bit) and infinity are refused too,
// an infinite stiffness or time step only blowing the run up later.
inline void require_finite(const char* name, double value, const char* bound) {
  if (std::isnan(value)) fail_input(name, " = nan must be a number ", bound);
  if (std::isinf(value)) fail_input(name, " = ", value, " must be finite");
}
inline void require_positive(const char* name, double value) {
  require_finite(name, value, "> 0");
  if (!(value > 0.0)) fail_input(name, " = ", value, " must be > 0");
}
inline void require_non_negative(const char* name, double value) {
  require_finite(name, value, ">= 0");
  if (!(value >= 0.0)) fail_input(name, " = ", value, " must be >= 0");
}

}  // namespace invasim
