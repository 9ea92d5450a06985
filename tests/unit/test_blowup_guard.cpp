// The blow-up guard (integrate/blowup_guard.hpp): check_blowup on prepared states (NaN, inf,
// sites beyond a wall by more or less than their diameter) and Dynamics::run stopping with a
// SimulationError at the expected step, naming the site, its kind and the value; a normal run
// passes; a genuine instability is reported identically with 1 and 2 threads.
#include <omp.h>
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <string>

#include "core/errors.hpp"
#include "integrate/blowup_guard.hpp"
#include "integrate/dynamics.hpp"
#include "test_support.hpp"

using namespace invasim;
using Catch::Matchers::Contains;
using Catch::Matchers::Matches;
using Catch::Matchers::StartsWith;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Restores the OpenMP thread count when a test ends (even by an exception).
struct ThreadGuard {
  int saved = omp_get_max_threads();
  ~ThreadGuard() { omp_set_num_threads(saved); }
};

// The message of the SimulationError that check_blowup throws ("" if it does not throw).
std::string check_message(const System& sys) {
  try {
    check_blowup(sys);
  } catch (const SimulationError& e) {
    return e.what();
  }
  return "";
}

// 8 adipocytes (damped vertices) and 60 cancer cells (Langevin, kT = 0) with contacts,
// walls and shape forces: every kind of site and force a production run has.
struct Setup {
  System sys = test::mixed_system(2, 60, 7.0, 0.2, 11);
  ForceField ff = test::standard_forces();
  Dynamics dyn{0.01};
  Setup() {
    dyn.add(Method::langevin(sys.sites_of_kind(SiteKind::kCancer), 0.2, 0.0));
    dyn.add(Method::damped(sys.sites_of_kind(SiteKind::kVertex), 0.2));
  }
  // Runs n steps; returns the SimulationError's message, or "" if the run completed.
  std::string run(std::uint64_t n) {
    try {
      dyn.run(sys, ff, n);
    } catch (const SimulationError& e) {
      return e.what();
    }
    return "";
  }
};

}  // namespace

TEST_CASE("check_blowup names the site, its kind and the offending value") {
  System sys = test::mixed_system(2, 20, 7.0, 0.2, 3);
  sys.step = 1234;
  CHECK(check_message(sys).empty());

  SECTION("a non-finite position of a cancer cell") {
    sys.sites().pos[17] = Vec3(kNaN, 1.25, 3.5);
    CHECK(check_message(sys) ==
          "blow-up at step 1234: site 17 (cancer cell) has a non-finite position (nan, 1.25, 3.5)");
  }
  SECTION("a non-finite velocity of an adipocyte vertex") {
    const int site = sys.bodies()[3].first_site + 5;
    sys.sites().vel[site] = Vec3(0.5, -kInf, 0.0);
    CHECK(check_message(sys) == "blow-up at step 1234: site " + std::to_string(site) +
                                    " (vertex 5 of adipocyte 3) has a non-finite velocity "
                                    "(0.5, -inf, 0)");
  }
  SECTION("the lowest site index is reported first, position before velocity") {
    sys.sites().vel[9] = Vec3(kNaN, 0, 0);
    sys.sites().pos[9] = Vec3(kInf, 1, 1);
    sys.sites().pos[12] = Vec3(kNaN, 1, 1);
    CHECK_THAT(check_message(sys), StartsWith("blow-up at step 1234: site 9 (cancer cell) has a "
                                              "non-finite position (inf, 1, 1)"));
  }
  SECTION("a site beyond a wall by more than its diameter") {
    const Box& box = sys.box();
    const double d = sys.sites().diameter[4];
    Vec3& r = sys.sites().pos[4];
    r[0] = box.hi()[0] + 0.99 * d;  // within one diameter: allowed while being pushed back
    CHECK(check_message(sys).empty());
    r[0] = box.lo()[0] - 0.99 * d;
    CHECK(check_message(sys).empty());
    r[0] = box.hi()[0] + 1.01 * d;
    CHECK_THAT(check_message(sys),
               StartsWith("blow-up at step 1234: site 4 (cancer cell) has left the box through "
                          "the upper x wall: x = "));
    r[0] = box.lo()[0] - 3.0;
    CHECK_THAT(check_message(sys), Contains("site 4 (cancer cell) has left the box through the "
                                            "lower x wall: x = -3 < lo.x - diameter = "));
  }
  SECTION("periodic axes are not walls") {
    sys.sites().pos[4][1] = sys.box().hi()[1] + 100.0;  // unwrapped on y: not an escape
    CHECK(check_message(sys).empty());
  }
}

TEST_CASE("check interval: default 100, configurable, at least 1") {
  Dynamics dyn(0.01);
  CHECK(dyn.check_every() == 100);
  dyn.set_check_every(7);
  CHECK(dyn.check_every() == 7);
  CHECK_THROWS_AS(dyn.set_check_every(0), InputError);
  CHECK(dyn.check_every() == 7);
}

TEST_CASE("a forced NaN velocity stops the run at the next check") {
  // Contact forces spread a NaN to the neighbours within a step; the lowest index affected is
  // reported, so the NaN is put on site 0.
  Setup s;
  SECTION("at a multiple of check_every") {
    s.dyn.set_check_every(10);
    s.sys.sites().vel[0] = Vec3(kNaN, 0.0, 0.0);
    CHECK_THAT(s.run(50), Matches("blow-up at step 10: site 0 \\(cancer cell\\) has a non-finite "
                                  "position \\(-?nan, [^)]*\\)"));
    CHECK(s.sys.step == 10);
  }
  SECTION("checks fall on multiples of the step count, not of the run's own steps") {
    s.sys.step = 95;
    s.sys.sites().vel[0] = Vec3(kNaN, 0.0, 0.0);
    CHECK_THAT(s.run(50), StartsWith("blow-up at step 100: site 0 (cancer cell)"));
    CHECK(s.sys.step == 100);
  }
  SECTION("at the end of a run shorter than check_every") {
    s.dyn.set_check_every(1000);
    s.sys.sites().vel[0] = Vec3(kNaN, 0.0, 0.0);
    CHECK_THAT(s.run(3), StartsWith("blow-up at step 3: site 0 (cancer cell)"));
    CHECK(s.sys.step == 3);
  }
  SECTION("an adipocyte vertex: the body's first vertex is reported") {
    // Shape forces only: the NaN spreads over the whole mesh (its volume), and no further.
    s.ff = ForceField();
    s.ff.add(std::make_shared<ShapeForce>(100.0, 1.0));
    s.dyn.set_check_every(5);
    const int first = s.sys.bodies()[2].first_site;
    s.sys.sites().vel[first + 7] = Vec3(0.0, kNaN, 0.0);
    CHECK_THAT(s.run(20), StartsWith("blow-up at step 5: site " + std::to_string(first) +
                                     " (vertex 0 of adipocyte 2) has a non-finite"));
  }
}

TEST_CASE("a site flying out through a wall stops the run") {
  Setup s;
  s.dyn.set_check_every(10);
  // Cancer cell 3 at 1000 sigma/tau outwards: far past the right wall within 10 steps.
  s.sys.sites().vel[3] = Vec3(1000.0, 0.0, 0.0);
  const std::string msg = s.run(100);
  CHECK_THAT(msg, StartsWith("blow-up at step 10: site 3 (cancer cell) has left the box through "
                             "the upper x wall: x = "));
  CHECK(s.sys.step == 10);
  CHECK(s.sys.sites().pos[3][0] > s.sys.box().hi()[0] + 50.0);
}

TEST_CASE("Box::wrap keeps the unwrapped position of a site just below the lower edge") {
  // r = -1e-17: r + L rounds to hi, which the round-off guard maps to lo; the image count must
  // not lose the period (it did: unwrapped -10, and again at every step the site stayed there).
  const Box box(Vec3(0.0, 0.0, 0.0), Vec3(10.0, 10.0, 10.0), {false, true, true});
  for (double y : {-1e-17, -4e-16, -1e-300, 10.0 - 1e-15, 20.0}) {
    Vec3 r(5.0, y, 5.0);
    Vec3i image(0, 2, 0);
    box.wrap(r, image);
    CHECK(r[1] >= 0.0);
    CHECK(r[1] < 10.0);
    CHECK(box.unwrap(r, image)[1] == Approx(y + 20.0).margin(1e-12));
  }
  System sys(box, 1);
  const int i = sys.add_sphere(Vec3(5.0, -1e-17, 5.0), 1.0);
  CHECK(sys.unwrapped(std::size_t(i))[1] == Approx(0.0).margin(1e-12));
}

TEST_CASE("a site flung beyond an int's image count along a periodic axis stops the run") {
  // Box::wrap cannot count 1e12 box lengths in an int image (the conversion was undefined
  // behaviour, caught by UBSan): the coordinate becomes infinite and the guard reports it.
  const Box box(Vec3(0.0, 0.0, 0.0), Vec3(10.0, 10.0, 10.0), {false, true, true});
  Vec3 r(5.0, 1e13, -1e13);
  Vec3i image(0, 3, 0);
  box.wrap(r, image);
  CHECK(r[0] == 5.0);
  CHECK(r[1] == kInf);
  CHECK(r[2] == -kInf);
  CHECK(image == Vec3i(0, 3, 0));
  // Near the limit an existing image count counts too.
  Vec3 q(5.0, 5.0 + 10.0 * 5e8, 5.0);
  Vec3i near(0, int(6e8), 0);
  box.wrap(q, near);
  CHECK(q[1] == kInf);
  CHECK(near[1] == int(6e8));
  // Ordinary crossings are still counted.
  Vec3 p(5.0, 25.0, -5.0);
  Vec3i counted(0, 0, 0);
  box.wrap(p, counted);
  CHECK(p[1] == Approx(5.0));
  CHECK(p[2] == Approx(5.0));
  CHECK(counted == Vec3i(0, 2, -1));

  Setup s;
  s.dyn.set_check_every(10);
  s.sys.sites().vel[3] = Vec3(0.0, 1e14, 0.0);  // > 1e9 box lengths in one step of the run
  CHECK_THAT(s.run(100), StartsWith("blow-up at step 10: site 3 (cancer cell) has a non-finite "
                                    "position"));
}

TEST_CASE("a normal run passes the checks") {
  Setup s;
  s.dyn.set_check_every(10);
  CHECK(s.run(300).empty());
  CHECK(s.sys.step == 300);
}

TEST_CASE("an escape is caught at the same step with 1 and 2 threads") {
  ThreadGuard guard;
  std::string message[2];
  std::uint64_t step[2] = {0, 0};
  for (int threads = 1; threads <= 2; ++threads) {
    omp_set_num_threads(threads);
    // 27 adipocytes and 300 cells (1434 sites: the force loops run in parallel). A
    // self-propulsion f0 = 2 beats the wall force of the large cells (at most 2 eps / 1.1
    // before they are one diameter beyond the wall): sooner or later one of them pushes
    // through a wall (the step depends on the noise; the run stops there, whatever the limit).
    System sys = test::mixed_system(3, 300, 7.0, 0.4, 21);
    ForceField ff = test::standard_forces();
    Dynamics dyn(0.05);
    dyn.step_threads().set_mode(StepThreads::Mode::kAll);  // at 2 threads: every step in the team
    auto active = Method::active(sys.sites_of_kind(SiteKind::kCancer), 5.0, 2.0, 10.0, 1e-3);
    active->randomize_orientations(sys);
    dyn.add(active);
    dyn.add(Method::damped(sys.sites_of_kind(SiteKind::kVertex), 0.2));
    dyn.set_check_every(5);
    try {
      dyn.run(sys, ff, 20000);
    } catch (const SimulationError& e) {
      message[threads - 1] = e.what();
    }
    step[threads - 1] = sys.step;
    INFO(threads << " threads: " << message[threads - 1] << " (step " << sys.step << ")");
    CHECK(dyn.parallel_steps() == (threads > 1 ? sys.step : 0u));  // every step in the team
    REQUIRE_THAT(message[threads - 1], Contains("(cancer cell) has left the box through the"));
  }
  CHECK(step[0] == step[1]);
  CHECK(step[0] % 5 == 0);
  CHECK(step[0] > 100);  // many steps of parallel force evaluation before the escape
  CHECK(message[0] == message[1]);
}
