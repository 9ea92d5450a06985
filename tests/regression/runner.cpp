// Data-driven force regression runner (in the manner of LAMMPS's unittest/force-styles): every
// tests/regression/*.force file holds a configuration, one force term's parameters and the
// reference energy, virial and per-site forces computed independently (generate.py). The
// engine builds the System and the term through its C++ API, evaluates it, and must match
// every value to a relative tolerance of 1e-12 (see kRelTol).
//
//   regression_forces                 all files in the source tree's tests/regression/
//   regression_forces --file a.force  only the given file(s) (CTest runs one file per test)
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include "regression_file.hpp"

using namespace invasim;
using namespace invasim::regression;

namespace {

std::vector<std::string> g_files;  // --file arguments

// The engine and the generator sum the same terms in different orders (neighbour-list order,
// per-site halves, Eigen vs math.fsum) and compute separations from differently wrapped
// positions, so results differ by a few ulps of the largest term involved. A value passes if
// |engine - reference| <= kRelTol * (|reference| + scale), scale being the largest magnitude
// of its group (all force components of the file; energy and virial components together).
constexpr double kRelTol = 1e-12;

std::vector<std::string> files_to_check() {
  if (!g_files.empty()) return g_files;
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(INVASIM_REGRESSION_DIR))
    if (entry.path().extension() == ".force") files.push_back(entry.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

// Compares one value; on failure records a message naming file, what and the numbers.
// Returns the deviation in units of the tolerance.
double compare(const std::string& path, const std::string& what, double got, double ref,
               double scale, int& failures) {
  const double tol = kRelTol * (std::abs(ref) + scale);
  const double diff = std::abs(got - ref);
  if (!(diff <= tol) && ++failures <= 12) {
    std::ostringstream msg;
    msg << std::setprecision(17) << path << ": " << what << " = " << got << ", reference " << ref
        << std::setprecision(3) << ", |diff| " << diff << " > tolerance " << tol;
    FAIL_CHECK(msg.str());
  }
  return diff / tol;
}

void check_file(const std::string& path) {
  const RegressionCase c = read_regression_file(path);
  System sys = build_system(c);
  REQUIRE(sys.n_sites() == c.forces.size());
  ForceField ff;
  ff.add(build_force(c, sys));
  const ForceResult r = ff.compute(sys, {true, true});

  int failures = 0;
  double worst = 0.0;
  const double scale_ev = std::max(std::abs(c.energy), c.virial.cwiseAbs().maxCoeff());
  worst = std::max(worst, compare(path, "energy", r.energy, c.energy, scale_ev, failures));
  for (int a = 0; a < 3; ++a)
    worst = std::max(worst, compare(path, std::string("virial W_") + "xyz"[a] + "xyz"[a],
                                    r.virial[a], c.virial[a], scale_ev, failures));
  double scale_f = 0.0;
  for (const Vec3& f : c.forces) scale_f = std::max(scale_f, f.cwiseAbs().maxCoeff());
  const auto& force = sys.sites().force;
  for (std::size_t i = 0; i < c.forces.size(); ++i)
    for (int a = 0; a < 3; ++a)
      worst = std::max(worst, compare(path, "site " + std::to_string(i) + " force " + "xyz"[a],
                                      force[i][a], c.forces[i][a], scale_f, failures));
  if (failures > 12) FAIL_CHECK(path << ": " << failures << " values differ in all");
  CHECK(failures == 0);
  if (std::getenv("INVASIM_TEST_VERBOSE"))
    std::printf("  %-40s %4zu sites  worst |diff| / tolerance = %.3g\n", path.c_str(),
                c.forces.size(), worst);
}

}  // namespace

TEST_CASE("force regression files match the engine", "[regression]") {
  const std::vector<std::string> files = files_to_check();
  REQUIRE_FALSE(files.empty());
  for (const std::string& path : files) {
    DYNAMIC_SECTION(std::filesystem::path(path).filename().string()) {
      check_file(path);
    }
  }
}

TEST_CASE("regression files: bad input is named with file and line", "[regression]") {
  const std::string path =
      (std::filesystem::temp_directory_path() / "invasim_bad_regression.force").string();
  auto attempt = [&](const std::string& text) {
    {
      std::ofstream out(path);
      out << text;
    }
    try {
      read_regression_file(path);
    } catch (const std::exception& e) {
      std::filesystem::remove(path);
      return std::string(e.what());
    }
    std::filesystem::remove(path);
    return std::string("no error");
  };
  using Catch::Matchers::Contains;
  CHECK_THAT(attempt("term contact\nfoo 1\n"), Contains(":2: unknown keyword 'foo'"));
  CHECK_THAT(attempt("term gravity\n"), Contains(":1: unknown term 'gravity'"));
  CHECK_THAT(attempt("term wall\nbox_lo 0 0 x\n"), Contains(":2: 'x' is not a number"));
  CHECK_THAT(attempt("term wall\nbox_lo 0 0 0\nbox_hi 1 1 1\nperiodic 0 1 1\nparam eps 1\n"
                     "param left 1\nparam right 1\nparam gamma 2\nenergy 0\nvirial 0 0 0\n"),
             Contains("unknown parameter 'gamma'"));
  CHECK_THAT(attempt("term shape\nbox_lo 0 0 0\nbox_hi 1 1 1\nperiodic 0 1 1\nparam eps_v 1\n"
                     "sphere 1 0.5 0.5 0.5\nenergy 0\nvirial 0 0 0\n"),
             Contains("0 force lines for 1 sites"));
  const std::string wall =
      "term wall\nbox_lo 0 0 0\nbox_hi 1 4 4\nperiodic 0 1 1\nparam eps 1\n"
      "param left 1\nparam right RIGHT\nsphere 1 X 2 2\nenergy 0\n"
      "virial 0 0 0\nforce 0 0 0 0\n";
  auto wall_with = [&](const std::string& right, const std::string& x) {
    std::string t = wall;
    t.replace(t.find("RIGHT"), 5, right);
    t.replace(t.find(" X "), 3, " " + x + " ");
    {
      std::ofstream out(path);
      out << t;
    }
    std::string result = "no error";
    try {
      const RegressionCase c = read_regression_file(path);
      const System sys = build_system(c);
      build_force(c, sys);
    } catch (const std::exception& e) {
      result = e.what();
    }
    std::filesystem::remove(path);
    return result;
  };
  CHECK(wall_with("1", "0.5") == "no error");
  CHECK_THAT(wall_with("1", "1.5"), Contains(path + ": site 0: x = 1.5 is outside the walls"));
  CHECK_THAT(wall_with("2", "0.5"), Contains(path + ": param right = 2 must be 0 (no wall) or 1"));
}

int main(int argc, char* argv[]) {
  Catch::Session session;
  using namespace Catch::clara;
  session.cli(session.cli() |
              Opt(g_files, "path")["--file"]("a regression file to check (repeatable)"));
  if (const int rc = session.applyCommandLine(argc, argv)) return rc;
  return session.run();
}
