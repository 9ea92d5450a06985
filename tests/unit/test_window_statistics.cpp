// The results table's window statistics (sweep/window_statistics.hpp), recomputed from a
// run's series.csv: the drift between the window's two halves is the second half's mean minus
// the first half's, with the sign of the trend, at every window length (2 and 3 rows included,
// where each half is one row).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "sweep/window_statistics.hpp"

using namespace invasim;
using namespace invasim::sweep;
namespace fs = std::filesystem;

namespace {

// A series.csv with columns step and "A_t [sigma^2]" holding the values y.
fs::path write_series(const char* name, const std::vector<double>& y) {
  const fs::path dir =
      fs::temp_directory_path() / ("invasim_window_statistics_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path path = dir / name;
  std::ofstream out(path);
  out << "step,A_t [sigma^2]\n";
  for (std::size_t k = 0; k < y.size(); ++k) out << k << "," << y[k] << "\n";
  return path;
}

}  // namespace

TEST_CASE("window statistics: the drift is the second half's mean minus the first half's",
          "[sweep]") {
  // A series rising by 1 per row: for a window of n rows the halves are its last 2 floor(n/2)
  // rows, floor(n/2) apart, so the drift is floor(n/2) at every n, never negative.
  std::vector<double> y;
  for (int k = 0; k < 12; ++k) y.push_back(100.0 + k);
  const fs::path series = write_series("rising.csv", y);
  for (int n : {2, 3, 4, 5, 8, 12}) {
    const auto stats = window_statistics(series, Json{{"A_t", {{"samples", n}}}});
    REQUIRE(stats.count("A_t") == 1);
    INFO("window of " << n << " rows");
    CHECK(stats.at("A_t").drift == Approx(double(n / 2)).epsilon(1e-12));
  }
  // Falling: the same drift with the opposite sign.
  for (double& v : y) v = -v;
  const fs::path falling = write_series("falling.csv", y);
  for (int n : {2, 3, 4}) {
    const auto stats = window_statistics(falling, Json{{"A_t", {{"samples", n}}}});
    REQUIRE(stats.count("A_t") == 1);
    INFO("window of " << n << " rows");
    CHECK(stats.at("A_t").drift == Approx(-double(n / 2)).epsilon(1e-12));
  }
  fs::remove_all(series.parent_path());
}
