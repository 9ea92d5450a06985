// Blocking error analysis (src/measure/block_average.hpp) against exact results: hand-worked
// levels, i.i.d. Gaussian samples (error sigma / sqrt(n)) and AR(1) series, whose standard
// error of the mean is known exactly, inflated over the naive one by ~sqrt((1+rho)/(1-rho)).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <vector>

#include "core/errors.hpp"
#include "core/rng.hpp"
#include "measure/block_average.hpp"

using namespace invasim;

namespace {

// Stationary AR(1) series with unit variance: x' = rho x + sqrt(1 - rho^2) e, e ~ N(0, 1).
std::vector<double> ar1(std::size_t n, double rho, std::uint64_t seed) {
  std::vector<double> x(n);
  const double s = std::sqrt(1.0 - rho * rho);
  std::array<double, 4> g{};
  for (std::size_t i = 0; i < n; ++i) {
    if (i % 4 == 0) g = RandomKey(seed, i / 4, 0, RngStream::kUser).normal4();
    x[i] = i == 0 ? g[0] : rho * x[i - 1] + s * g[i % 4];
  }
  return x;
}

// Exact standard error of the mean of n samples of the unit-variance AR(1) series.
double ar1_error(std::size_t n, double rho) {
  const double N = double(n);
  return std::sqrt(
      ((1 + rho) / (1 - rho) - 2 * rho * (1 - std::pow(rho, N)) / (N * (1 - rho) * (1 - rho))) / N);
}

struct Ensemble {
  double mean_error = 0.0;  // mean of the reported errors
  double scatter = 0.0;     // standard deviation of the means over the series
  double worst = 0.0;       // largest |reported / exact - 1| of one series
  int plateaus = 0;
};

Ensemble analyse(int series, std::size_t n, double rho, std::uint64_t seed, double exact) {
  Ensemble e;
  double m1 = 0.0, m2 = 0.0;
  for (int k = 0; k < series; ++k) {
    const std::vector<double> x = ar1(n, rho, seed + std::uint64_t(k));
    const BlockAverage b = block_average(x);
    e.mean_error += b.error / series;
    e.worst = std::max(e.worst, std::abs(b.error / exact - 1.0));
    e.plateaus += b.plateau;
    m1 += b.mean / series;
    m2 += b.mean * b.mean / series;
  }
  e.scatter = std::sqrt((m2 - m1 * m1) * series / (series - 1.0));
  return e;
}

}  // namespace

TEST_CASE("blocking levels of a short series by hand", "[blocking]") {
  const std::vector<double> x = {1, 2, 3, 4, 5};
  const BlockAverage b = block_average(x);
  CHECK(b.n == 5);
  CHECK(b.mean == 3.0);
  REQUIRE(b.levels.size() == 2);  // 5 samples, then 2 blocks (the fifth sample dropped)
  // Level 0: variance of {1..5} about 3 = 2, error sqrt(2 / 4).
  CHECK(b.levels[0].block_size == 1);
  CHECK(b.levels[0].n_blocks == 5);
  CHECK(b.levels[0].error == Approx(std::sqrt(0.5)).epsilon(1e-14));
  CHECK(b.levels[0].error_of_error == Approx(std::sqrt(0.5) / std::sqrt(8.0)).epsilon(1e-14));
  // Level 1: blocks 1.5 and 3.5, variance 1, error sqrt(1 / 1).
  CHECK(b.levels[1].block_size == 2);
  CHECK(b.levels[1].n_blocks == 2);
  CHECK(b.levels[1].error == Approx(1.0).epsilon(1e-14));
  CHECK(b.naive_error == b.levels[0].error);
  // Fewer samples than min_blocks (16): level 0 is reported, without a plateau.
  CHECK_FALSE(b.plateau);
  CHECK(b.error == b.levels[0].error);
}

TEST_CASE("blocking of degenerate series", "[blocking]") {
  CHECK(std::isnan(block_average(std::vector<double>{}).mean));
  const BlockAverage one = block_average(std::vector<double>{2.5});
  CHECK(one.mean == 2.5);
  CHECK(std::isnan(one.error));
  const BlockAverage flat = block_average(std::vector<double>(1000, 0.75));
  CHECK(flat.mean == 0.75);
  CHECK(flat.error == 0.0);
  CHECK(flat.plateau);
  CHECK(flat.block_size == 1);
  CHECK_THROWS_AS(block_average(std::vector<double>{1, 2}, BlockingOptions{1}), InputError);
}

TEST_CASE("i.i.d. Gaussian samples: error = sigma / sqrt(n)", "[blocking]") {
  // 100 series of 2^16 unit normals: the reported error averages to 1/sqrt(n) (each to
  // ~2%), and the means scatter by as much.
  const std::size_t n = 1 << 16;
  const double exact = 1.0 / std::sqrt(double(n));
  const Ensemble e = analyse(100, n, 0.0, 0x11D0ull, exact);
  std::printf(
      "[blocking] iid, n = 2^16: <error> / exact = %.4f, worst series %.3f, scatter of the "
      "means / exact = %.3f, plateaus %d/100\n",
      e.mean_error / exact, e.worst, e.scatter / exact, e.plateaus);
  CHECK(std::abs(e.mean_error / exact - 1.0) < 0.02);
  CHECK(e.worst < 0.15);
  CHECK(std::abs(e.scatter / exact - 1.0) < 0.2);  // 100 series: ~7% statistical
  CHECK(e.plateaus == 100);
}

TEST_CASE("AR(1) series: error inflated by sqrt((1+rho)/(1-rho)), the plateau found",
          "[blocking]") {
  for (const double rho : {0.5, 0.9}) {
    const std::size_t n = 1 << 18;
    const double exact = ar1_error(n, rho);
    const Ensemble e = analyse(60, n, rho, 0xA400ull + std::uint64_t(rho * 100), exact);
    const BlockAverage one = block_average(ar1(n, rho, 0xB0ull));
    std::printf(
        "[blocking] AR(1) rho = %.1f, n = 2^18: <error> / exact = %.4f (worst series %.3f), "
        "scatter of the means / exact = %.3f, naive / exact = %.4f (expected %.4f), "
        "block size %zu, plateaus %d/60\n",
        rho, e.mean_error / exact, e.worst, e.scatter / exact, one.naive_error / exact,
        1.0 / std::sqrt((1 + rho) / (1 - rho)), one.block_size, e.plateaus);
    CHECK(std::abs(e.mean_error / exact - 1.0) < 0.03);
    CHECK(e.worst < 0.25);
    CHECK(std::abs(e.scatter / exact - 1.0) < 0.25);  // 60 series: ~9% statistical
    CHECK(e.plateaus == 60);
    // The naive error is too small by the inflation factor.
    CHECK(one.naive_error / exact == Approx(1.0 / std::sqrt((1 + rho) / (1 - rho))).epsilon(0.03));
    CHECK(one.error > 0.8 * exact);
  }
}

TEST_CASE("a series too short for its correlation time has no plateau", "[blocking]") {
  // rho = 0.999: tau_int ~ 1000 samples, n = 4096. The error reported (a lower bound) is far
  // below the exact one, and the result says so.
  const std::size_t n = 4096;
  const BlockAverage b = block_average(ar1(n, 0.999, 0xC0ull));
  std::printf("[blocking] rho = 0.999, n = 4096: error / exact = %.3f, plateau %d\n",
              b.error / ar1_error(n, 0.999), int(b.plateau));
  CHECK_FALSE(b.plateau);
  CHECK(b.error < 0.5 * ar1_error(n, 0.999));  // 0.27 of the exact error here
  CHECK(b.n_blocks == 16);                     // the last level with min_blocks blocks
}

TEST_CASE("tail averages", "[blocking]") {
  std::vector<double> x(1000);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = i < 500 ? 100.0 : double(i % 7);
  const BlockAverage tail = block_average_tail(x, 0.5);
  const BlockAverage direct = block_average(std::vector<double>(x.begin() + 500, x.end()));
  CHECK(tail.n == 500);
  CHECK(tail.mean == direct.mean);
  CHECK(tail.error == direct.error);
  CHECK(block_average_tail(x, 0.25).n == 250);
  CHECK(block_average_tail(x, 1.0).n == 1000);
  CHECK_THROWS_AS(block_average_tail(x, 0.0), InputError);
  CHECK_THROWS_AS(block_average_tail(x, 1.5), InputError);
}
