// The contact kernel's two drivers (docs/performance.md, "Round 4: half-list kernel on one
// thread"): the half rows on one thread (each pair once, scattered) and the full rows (any
// thread count) give exactly the same forces, energy and virial, bit for bit.
#include <omp.h>
#include <catch2/catch.hpp>

#include <memory>
#include <string>
#include <vector>

#include "integrate/step_threads.hpp"
#include "test_support.hpp"

using namespace invasim;
using namespace invasim::test;

namespace {

struct Outcome {
  std::vector<Vec3> force;
  double energy = 0.0;
  Vec3 virial = Vec3::Zero();
};

// Contact forces of sys with the given driver on `threads` threads. The forces start from a
// non-zero value (another term's) so that the drivers' "+=" is checked too.
Outcome evaluate(const System& start, const ContactParams& p, ContactKernel kernel, int threads,
                 const ForceFlags& flags) {
  System sys = start;
  const ThreadCountScope scope(threads);
  ContactForce contact(p);
  contact.set_kernel(kernel);
  for (std::size_t i = 0; i < sys.n_sites(); ++i) sys.sites().force[i] = Vec3(0.25, -0.5, 1.0);
  const ForceResult r = contact.add_forces(sys, flags);
  return {sys.sites().force, r.energy, r.virial};
}

// Pairs of cancer cells on the attractive branch (r_b < r < r_a) and coincident pairs.
std::pair<int, int> count_pairs(const System& sys, const ContactParams& p) {
  const MinimumImage image(sys.box());
  const Sites& s = sys.sites();
  int attractive = 0, coincident = 0;
  for (std::size_t i = 0; i < s.size(); ++i)
    for (std::size_t j = i + 1; j < s.size(); ++j) {
      const Vec3 d(image.x(s.pos[i][0] - s.pos[j][0]), image.y(s.pos[i][1] - s.pos[j][1]),
                   image.z(s.pos[i][2] - s.pos[j][2]));
      const double r = d.norm(), sd = 0.5 * (s.diameter[i] + s.diameter[j]);
      const bool cc = s.kind[i] == SiteKind::kCancer && s.kind[j] == SiteKind::kCancer;
      if (cc && r > (1 + p.beta) * sd && r < (1 + p.alpha) * sd) ++attractive;
      if (r == 0.0) ++coincident;
    }
  return {attractive, coincident};
}

void check_drivers_agree(const System& sys, const ContactParams& p) {
  for (const ForceFlags flags : {ForceFlags{false, false}, ForceFlags{true, false},
                                 ForceFlags{false, true}, ForceFlags{true, true}}) {
    CAPTURE(flags.energy, flags.virial);
    const Outcome full2 = evaluate(sys, p, ContactKernel::kFullRows, 2, flags);
    const Outcome full1 = evaluate(sys, p, ContactKernel::kFullRows, 1, flags);
    const Outcome half = evaluate(sys, p, ContactKernel::kHalfRows, 1, flags);
    const Outcome automatic1 = evaluate(sys, p, ContactKernel::kAuto, 1, flags);
    const Outcome automatic2 = evaluate(sys, p, ContactKernel::kAuto, 2, flags);
    std::size_t differ = 0;
    for (std::size_t i = 0; i < sys.n_sites(); ++i) differ += half.force[i] != full2.force[i];
    CHECK(differ == 0);
    CHECK(half.force == full2.force);
    CHECK(half.force == full1.force);
    CHECK(automatic1.force == full2.force);
    CHECK(automatic2.force == full2.force);
    CHECK(half.energy == full2.energy);
    CHECK(half.virial == full2.virial);
    CHECK(automatic1.energy == full2.energy);
    CHECK(automatic1.virial == full2.virial);
    if (flags.energy) CHECK(half.energy != 0.0);
    if (flags.virial) CHECK(half.virial.norm() > 0.0);
  }
}

}  // namespace

TEST_CASE(
    "contact kernel: the half rows on one thread and the full rows on 1 and 2 threads give "
    "bit-identical forces, energy and virial") {
  ContactParams repulsive;
  ContactParams cohesive;
  cohesive.alpha = 0.2;
  cohesive.beta = 1e-2;
  cohesive.eps_cv = 0.7;
  cohesive.eps_vv = 1.3;

  SECTION("repulsive spheres, with two coincident pairs (one in a periodic image)") {
    System sys = random_spheres(2000, 0.65, false, 41);
    REQUIRE(sys.n_sites() >= 1024);  // the full rows run on 2 threads
    sys.sites().pos[7] = sys.sites().pos[1500];
    sys.sites().pos[20] = sys.sites().pos[3];
    CHECK(count_pairs(sys, repulsive).second == 2);
    check_drivers_agree(sys, repulsive);
  }
  SECTION("cohesive spheres: pairs on the repulsive and the attractive branch, coincident pair") {
    System sys = random_spheres(2000, 0.65, false, 42);
    sys.sites().pos[11] = sys.sites().pos[5];
    const auto [attractive, coincident] = count_pairs(sys, cohesive);
    CHECK(attractive > 500);
    CHECK(coincident == 1);
    check_drivers_agree(sys, cohesive);
  }
  SECTION("adipocyte vertices and cancer cells (mixed system), cohesive, coincident mixed pair") {
    System sys = mixed_system(3, 400, 4.6, 0.4, 11);
    REQUIRE(sys.n_sites() >= 1024);
    REQUIRE(sys.sites().kind.back() == SiteKind::kVertex);
    sys.sites().pos[0] = sys.sites().pos.back();  // a cancer cell on a vertex
    PairTable table;
    REQUIRE(table.build(sys.sites(), cohesive));
    CHECK(count_pairs(sys, cohesive).first > 50);
    check_drivers_agree(sys, cohesive);
  }
  SECTION("more than 16 diameter classes: the constants from the diameters (no table)") {
    System sys = mixed_system(3, 400, 4.6, 0.4, 12);
    for (std::size_t i = 0; i < sys.n_sites(); ++i)
      if (sys.sites().kind[i] == SiteKind::kCancer)
        sys.sites().diameter[i] = 0.9 + 0.01 * double(i % 20);
    sys.sites().pos[1] = sys.sites().pos[2];
    PairTable table;
    REQUIRE_FALSE(table.build(sys.sites(), cohesive));
    CHECK(count_pairs(sys, cohesive).first > 50);
    check_drivers_agree(sys, cohesive);
  }
}
