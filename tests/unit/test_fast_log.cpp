// core/fast_log.hpp against libm: within 1 ulp over the uniforms the orientation update draws
// ((k + 0.5) 2^-32, every scale down to 2^-33) and over normal numbers of every binade, exact
// at 1, and the same numbers in a vectorised loop as one by one.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/fast_log.hpp"

namespace {

// Distance in units in the last place of the reference.
double ulps(double got, double want) {
  if (got == want) return 0.0;
  return std::abs(got - want) / (std::nextafter(std::abs(want), INFINITY) - std::abs(want));
}

}  // namespace

TEST_CASE("fast log: within 1 ulp of libm on the uniforms and on every binade") {
  double worst = 0.0, at = 0.0;
  auto check = [&](double x) {
    const double e = ulps(invasim::fast_log::log(x), std::log(x));
    if (e > worst) worst = e, at = x;
  };
  std::uint64_t state = 0x9E3779B97F4A7C15ull;
  for (int i = 0; i < 2000000; ++i) {  // the uniforms of RandomKey::uniform
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    check((double(std::uint32_t(state >> 32)) + 0.5) * 0x1p-32);
  }
  for (int e = -1022; e < 1024; ++e)  // every binade, near sqrt(2) and at the edges
    for (double m : {1.0, 1.0000000000000002, 1.25, 1.4142135623730949, 1.4142135623730951, 1.5,
                     1.9999999999999998})
      check(std::ldexp(m, e));
  INFO("worst " << worst << " ulp at x = " << at);
  CHECK(worst <= 1.0);
  CHECK(invasim::fast_log::log(1.0) == 0.0);
}

TEST_CASE("fast log: a vectorised loop gives the same bits as one call at a time") {
  std::vector<double> x(1000), a(1000), b(1000);
  for (int i = 0; i < 1000; ++i) x[i] = (i + 0.5) / 1000.0;
#pragma omp simd
  for (int i = 0; i < 1000; ++i) a[i] = invasim::fast_log::log(x[i]);
  for (int i = 0; i < 1000; ++i) {
    volatile double xi = x[i];
    b[i] = invasim::fast_log::log(xi);
  }
  CHECK(a == b);
}
