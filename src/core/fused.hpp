#pragma once
// a * b + c with one rounding where the target has fused multiply-add instructions, with two
// where it has none; the same bits in a vector lane and in scalar code either way. GCC fuses
// `a * b + c` written out or not depending on the surrounding code (-ffp-contract=fast), so a
// loop whose scalar remainder and vector body must agree (results independent of the thread
// count) states the fusion explicitly.
#include <cmath>

namespace invasim {

[[gnu::always_inline]] inline double mul_add(double a, double b, double c) {
#if defined(__FP_FAST_FMA)
  return std::fma(a, b, c);
#else
  return a * b + c;  // (no FMA instruction: nothing to contract either)
#endif
}

}  // namespace invasim
