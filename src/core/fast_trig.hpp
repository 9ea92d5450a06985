#pragma once
// Branch-free sin, cos and sinc = sin(x)/x for loops the compiler vectorises (`#pragma omp
// simd`): the correlator's F_s (time_correlator.cpp) evaluates one per (time origin, site)
// pair, where libm's sin cost ~70 % of all the correlator's time; the active cells'
// orientation update (integrate/dynamics.cpp) takes three sine-cosine pairs per cell and step
// from `sincos`. Plain C++ (no intrinsics): every target gets the same results, vectorised or
// not, for a given compiler and flags.
//
// Method (fdlibm's, without its branches): x = n pi/2 + y with n = round(2x/pi) and the
// reduction y = (((x - n P1) - n P2) - n P3) - n P4 in four parts of pi/2 (P1, P2, P3 of 33
// bits, so n P1, n P2, n P3 are exact for n < 2^20 and the first subtraction is exact; each
// later one rounds relative to its result, so y is accurate to a few ulp even where x is
// closest to a multiple of pi/2), then fdlibm's
// minimax polynomials for sin and cos on |y| <= pi/4 (error < 1 ulp each), chosen and signed
// by n mod 4. Measured against std::sin / std::cos: a few 1e-16 relative (tests/unit/
// test_fast_trig.cpp). Valid for 0 <= x <= kMaxArg; larger arguments need std::sin.
#include <bit>
#include <cstdint>

namespace invasim::fast_trig {

// Largest argument reduced exactly (n < 2^20 needs x < 2^20 pi/2 = 1.647e6).
inline constexpr double kMaxArg = 1.0e6;

namespace detail {
inline constexpr double kTwoOverPi = 6.36619772367581382433e-01;
inline constexpr double kPio2_1 = 1.57079632673412561417e+00;   // first 33 bits of pi/2
inline constexpr double kPio2_2 = 6.07710050630396597660e-11;   // next 33 bits
inline constexpr double kPio2_3 = 2.02226624871116645580e-21;   // next 33 bits
inline constexpr double kPio2_3t = 8.47842766036889956997e-32;  // the rest
inline constexpr double kShifter = 0x1.8p52;  // x + kShifter rounds x to an integer
// fdlibm k_sin.c / k_cos.c
inline constexpr double S1 = -1.66666666666666324348e-01, S2 = 8.33333333332248946124e-03,
                        S3 = -1.98412698298579493134e-04, S4 = 2.75573137070700676789e-06,
                        S5 = -2.50507602534068634195e-08, S6 = 1.58969099521155010221e-10;
inline constexpr double C1 = 4.16666666666666019037e-02, C2 = -1.38888888888741095749e-03,
                        C3 = 2.48015872894767294178e-05, C4 = -2.75573143513906633035e-07,
                        C5 = 2.08757232129817482790e-09, C6 = -1.13596475577881948265e-11;
}  // namespace detail

// The reduced argument of 0 <= x <= kMaxArg: x = n pi/2 + y, |y| <= pi/4, with sin(y),
// cos(y) and n's last bits (q).
struct Reduced {
  double sin_y, cos_y;
  std::uint64_t q;
};
inline Reduced reduce(double x) {
  using namespace detail;
  const double t = x * kTwoOverPi + kShifter;
  // t's last mantissa bits hold n (t = 1.5 2^52 + n, spacing 1).
  const std::uint64_t q = std::bit_cast<std::uint64_t>(t);
  const double n = t - kShifter;
  const double y = (((x - n * kPio2_1) - n * kPio2_2) - n * kPio2_3) - n * kPio2_3t;
  const double z = y * y, w = z * z;
  const double rs = S2 + z * (S3 + z * S4) + z * w * (S5 + z * S6);
  const double sin_y = y + z * y * (S1 + z * rs);
  const double rc = z * (C1 + z * (C2 + z * C3)) + w * w * (C4 + z * (C5 + z * C6));
  const double hz = 0.5 * z, one_hz = 1.0 - hz;
  const double cos_y = one_hz + (((1.0 - one_hz) - hz) + z * rc);
  return {sin_y, cos_y, q};
}

// sin(x + q0 pi/2) for 0 <= x <= kMaxArg (q0 = 0: sin, q0 = 1: cos).
inline double sin_quarter_shifted(double x, std::uint64_t q0) {
  const Reduced r = reduce(x);
  const std::uint64_t q = r.q + q0;
  const double s = (q & 1) ? r.cos_y : r.sin_y;
  return (q & 2) ? -s : s;
}

inline double sin(double x) {
  return sin_quarter_shifted(x, 0);
}
inline double cos(double x) {
  return sin_quarter_shifted(x, 1);
}

// sin(x) and cos(x) for |x| <= kMaxArg from one reduction (the same values as sin(|x|),
// cos(|x|) above, sin's sign following x's).
inline void sincos(double x, double& sin_x, double& cos_x) {
  const double a = x < 0.0 ? -x : x;
  const Reduced r = reduce(a);
  const double s = (r.q & 1) ? r.cos_y : r.sin_y;  // sin(a) up to sign
  const double c = (r.q & 1) ? r.sin_y : r.cos_y;  // cos(a) up to sign
  sin_x = ((r.q & 2) ? -s : s) * (x < 0.0 ? -1.0 : 1.0);
  cos_x = ((r.q + 1) & 2) ? -c : c;
}

// sin(x)/x for 0 <= x <= kMaxArg, exactly 1 at 0 (Taylor below 1e-4, where the next term is
// below 1e-18; x^2 times a rounded 1/6, which costs no second division in a vector loop).
inline double sinc(double x) {
  const bool small = x < 1e-4;
  const double s = sin(x) / (small ? 1.0 : x);
  return small ? 1.0 - x * x * (1.0 / 6.0) : s;
}

}  // namespace invasim::fast_trig
