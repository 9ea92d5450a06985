// The vectorisable sin, cos and sinc of src/core/fast_trig.hpp (the correlator's F_s)
// against libm over their whole range [0, kMaxArg], including the arguments closest to the
// multiples of pi/2, where the range reduction loses the most.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "core/fast_trig.hpp"

using namespace invasim;

namespace {

// |a - b| in units in the last place of b.
double ulps(double a, double b) {
  const double ulp = std::nextafter(std::abs(b), INFINITY) - std::abs(b);
  return std::abs(a - b) / ulp;
}

}  // namespace

TEST_CASE("fast sin and cos agree with libm to 2 ulp on [0, 1e6]") {
  std::mt19937_64 gen(5);
  double worst_sin = 0.0, worst_cos = 0.0;
  auto check = [&](double x) {
    worst_sin = std::max(worst_sin, ulps(fast_trig::sin(x), std::sin(x)));
    worst_cos = std::max(worst_cos, ulps(fast_trig::cos(x), std::cos(x)));
  };
  // Uniform on [0, 10^e] for every decade down to 1e-8 ...
  for (int e = -8; e <= 6; ++e) {
    std::uniform_real_distribution<double> u(0.0, std::pow(10.0, e));
    for (int i = 0; i < 20000; ++i) check(std::min(u(gen), fast_trig::kMaxArg));
  }
  // ... and the doubles next to n pi/2, where sin or cos is smallest.
  for (long n = 1; n * M_PI_2 < fast_trig::kMaxArg; n += 97) {
    double x = double(n) * M_PI_2;
    for (int k = 0; k < 3; ++k, x = std::nextafter(x, INFINITY)) check(x);
  }
  check(0.0);
  check(fast_trig::kMaxArg);
  INFO("sin " << worst_sin << " ulp, cos " << worst_cos << " ulp");
  CHECK(worst_sin <= 2.0);
  CHECK(worst_cos <= 2.0);
  CHECK(fast_trig::sin(0.0) == 0.0);
  CHECK(fast_trig::cos(0.0) == 1.0);
}

TEST_CASE("fast sinc: exactly 1 at 0, 1e-15 relative to sin(x)/x elsewhere") {
  CHECK(fast_trig::sinc(0.0) == 1.0);
  CHECK(fast_trig::sinc(1e-5) == 1.0 - 1e-10 / 6.0);  // Taylor below 1e-4
  std::mt19937_64 gen(6);
  double worst = 0.0;
  for (int e = -4; e <= 6; ++e) {
    std::uniform_real_distribution<double> u(1e-4, std::pow(10.0, e));
    for (int i = 0; i < 20000; ++i) {
      const double x = std::min(u(gen), fast_trig::kMaxArg), ref = std::sin(x) / x;
      worst = std::max(worst, std::abs(fast_trig::sinc(x) - ref) / std::abs(ref));
    }
  }
  INFO("worst relative difference " << worst);
  CHECK(worst <= 1e-15);
}

TEST_CASE("fast sincos: both from one reduction, odd and even, within 2 ulp of libm") {
  std::mt19937_64 gen(7);
  double worst_sin = 0.0, worst_cos = 0.0;
  auto check = [&](double x) {
    double s = 0.0, c = 0.0;
    fast_trig::sincos(x, s, c);
    // Odd and even exactly: sin(-x) = -sin(x), cos(-x) = cos(x), bit for bit.
    double s_neg = 0.0, c_neg = 0.0;
    fast_trig::sincos(-x, s_neg, c_neg);
    REQUIRE(s_neg == -s);
    REQUIRE(c_neg == c);
    worst_sin = std::max(worst_sin, ulps(s, std::sin(x)));
    worst_cos = std::max(worst_cos, ulps(c, std::cos(x)));
  };
  // The orientation update's arguments: [0, 2 pi) for the azimuths, small angles of either
  // sign for the rotation, and every quadrant around the multiples of pi/2.
  std::uniform_real_distribution<double> azimuth(0.0, 2.0 * M_PI), small(-0.5, 0.5);
  for (int i = 0; i < 100000; ++i) {
    check(azimuth(gen));
    check(small(gen));
  }
  for (int n = -40; n <= 40; ++n) {
    double x = n * M_PI_2;
    for (int k = 0; k < 3; ++k, x = std::nextafter(x, INFINITY)) check(x);
  }
  INFO("sin " << worst_sin << " ulp, cos " << worst_cos << " ulp");
  CHECK(worst_sin <= 2.0);
  CHECK(worst_cos <= 2.0);
  double s = 1.0, c = 0.0;
  fast_trig::sincos(0.0, s, c);
  CHECK(s == 0.0);
  CHECK(c == 1.0);
  fast_trig::sincos(M_PI, s, c);
  CHECK(std::abs(s) < 1e-15);
  CHECK(c == -1.0);
}
