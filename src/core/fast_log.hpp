#pragma once
// A branch-free natural logarithm for loops the compiler vectorises (`#pragma omp simd`): the
// active cells' orientation update (integrate/dynamics.cpp) takes one per cell and step for
// its Box-Muller angle, where libm's scalar log was 2 % of a paper-size production. Plain C++
// (no intrinsics), like core/fast_trig.hpp.
//
// Method (fdlibm's e_log.c, without its branches): x = 2^k m with sqrt(2)/2 <= m < sqrt(2),
// f = m - 1, s = f/(2 + f), and log(1 + f) = f - hfsq + s (hfsq + R(s^2)), hfsq = f^2/2, R
// fdlibm's minimax polynomial (error < 1 ulp); k ln 2 added in two parts. Valid for normal
// positive finite x (2^-1022 <= x < inf); the callers pass uniforms in (2^-33, 1). Measured
// against std::log: within 1 ulp (tests/unit/test_fast_log.cpp).
#include <bit>
#include <cstdint>

namespace invasim::fast_log {

namespace detail {
inline constexpr double kLn2Hi = 6.93147180369123816490e-01;  // 32 bits of ln 2
inline constexpr double kLn2Lo = 1.90821492927058770002e-10;  // the rest
// fdlibm e_log.c
inline constexpr double Lg1 = 6.666666666666735130e-01, Lg2 = 3.999999999940941908e-01,
                        Lg3 = 2.857142874366239149e-01, Lg4 = 2.222219843214978396e-01,
                        Lg5 = 1.818357216161805012e-01, Lg6 = 1.531383769920937332e-01,
                        Lg7 = 1.479819860511658591e-01;
}  // namespace detail

// log(x) for normal positive finite x.
inline double log(double x) {
  using namespace detail;
  const std::uint64_t bits = std::bit_cast<std::uint64_t>(x);
  // m in [1, 2) from the mantissa; halved (k + 1) when above sqrt(2).
  const std::uint64_t mantissa = bits & 0x000FFFFFFFFFFFFFull;
  const double m1 = std::bit_cast<double>(mantissa | 0x3FF0000000000000ull);
  const bool high = m1 > 1.41421356237309504880;
  const double m = high ? 0.5 * m1 : m1;
  const double k = double(std::int64_t((bits >> 52) & 0x7FF) - 1023 + (high ? 1 : 0));
  const double f = m - 1.0;
  const double s = f / (2.0 + f), z = s * s, w = z * z;
  const double t1 = w * (Lg2 + w * (Lg4 + w * Lg6));
  const double t2 = z * (Lg1 + w * (Lg3 + w * (Lg5 + w * Lg7)));
  const double r = t2 + t1, hfsq = 0.5 * f * f;
  return k * kLn2Hi - ((hfsq - (s * (hfsq + r) + k * kLn2Lo)) - f);
}

}  // namespace invasim::fast_log
