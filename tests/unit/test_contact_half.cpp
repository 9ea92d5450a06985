// The contact kernel's two drivers (docs/performance.md, "Half rows"): the half rows (each pair
// once, scattered, on any number of threads and for any owner of the sites) and the full rows give
// exactly the same forces, energy and virial, bit for bit.
#include <omp.h>
#include <catch2/catch.hpp>

#include <memory>
#include <random>
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
    CHECK(full1.force == full2.force);
    // The half rows on 1, 2, 3 and 4 threads (slabs along different axes and numbers of cuts).
    for (const int threads : {1, 2, 3, 4}) {
      CAPTURE(threads);
      const Outcome half = evaluate(sys, p, ContactKernel::kHalfRows, threads, flags);
      std::size_t differ = 0;
      for (std::size_t i = 0; i < sys.n_sites(); ++i) differ += half.force[i] != full2.force[i];
      CHECK(differ == 0);
      CHECK(half.energy == full2.energy);
      CHECK(half.virial == full2.virial);
      if (flags.energy) CHECK(half.energy != 0.0);
      if (flags.virial) CHECK(half.virial.norm() > 0.0);
    }
  }
}

// The contact forces of sys from half-row plans of an arbitrary owner assignment, each
// thread's plan run in turn on the calling thread (the partition is free to be anything).
std::vector<Vec3> forces_of_owners(const System& start, const ContactParams& p,
                                   const std::vector<int>& owner, int parts) {
  System sys = start;
  VerletList list(p.skin);
  CutoffRule rule;
  rule.factor[0][0] = p.beta > 0.0 ? 1.0 + p.alpha : 1.0;
  list.set_cutoff_rule(rule);
  list.build(sys);
  PairTable table;
  table.build(sys.sites(), p);
  const std::size_t n = sys.n_sites();
  std::vector<int> rank(n);
  contact_detail::RowScratch scratch;
  for (auto& f : sys.sites().force) f = Vec3(0.25, -0.5, 1.0);
  for (int t = 0; t < parts; ++t) {
    HalfRowsPlan plan;
    plan_half_rows(list, owner, t, rank, plan);
    contact_half_rows<true, false, false>(sys, plan, list.max_count(), table, p, nullptr, nullptr,
                                          scratch);
  }
  return sys.sites().force;
}

// Entries of the plans of `parts` threads (pairs computed, halo rows included) over the
// pairs of the list (each counted once).
double entries_over_pairs(const System& start, const ContactParams& p, int parts) {
  System sys = start;
  VerletList list(p.skin);
  list.build(sys);
  std::vector<int> owner;
  partition_sites(sys, list, parts, owner);
  std::vector<int> rank(sys.n_sites());
  std::size_t entries = 0, pairs = 0;
  for (std::size_t i = 0; i < sys.n_sites(); ++i) pairs += std::size_t(list.count(i));
  for (int t = 0; t < parts; ++t) {
    HalfRowsPlan plan;
    plan_half_rows(list, owner, t, rank, plan);
    entries += plan.partner.size();
  }
  return double(entries) / (0.5 * double(pairs));
}

}  // namespace

TEST_CASE(
    "contact kernel: the half rows on 1 to 4 threads and the full rows on 1 and 2 threads give "
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
  SECTION("cancer-vertex adhesion beside the cells' cohesion, with and without the table") {
    ContactParams adhesive = cohesive;
    adhesive.alpha_cv = 0.3;
    adhesive.beta_cv = 0.05;
    System sys = mixed_system(3, 400, 4.6, 0.4, 13);
    PairTable table;
    REQUIRE(table.build(sys.sites(), adhesive));
    check_drivers_agree(sys, adhesive);
    for (std::size_t i = 0; i < sys.n_sites(); ++i)  // more classes than the table holds
      if (sys.sites().kind[i] == SiteKind::kCancer)
        sys.sites().diameter[i] = 0.9 + 0.01 * double(i % 20);
    REQUIRE_FALSE(table.build(sys.sites(), adhesive));
    check_drivers_agree(sys, adhesive);
  }
  SECTION("6 classes: the table looked up by loads (more class pairs than a permute holds)") {
    System sys = mixed_system(3, 400, 4.6, 0.4, 14);
    for (std::size_t i = 0; i < sys.n_sites(); ++i)
      if (sys.sites().kind[i] == SiteKind::kCancer)
        sys.sites().diameter[i] = 0.9 + 0.05 * double(i % 5);
    PairTable table;
    REQUIRE(table.build(sys.sites(), cohesive));
    REQUIRE(table.n_classes() == 6);
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

TEST_CASE("contact kernel: the half rows give the same bits for any owner of the sites") {
  ContactParams cohesive;
  cohesive.beta = 1e-2;
  const System sys = mixed_system(3, 400, 4.6, 0.4, 13);
  const std::size_t n = sys.n_sites();
  const Outcome full = evaluate(sys, cohesive, ContactKernel::kFullRows, 1, {false, false});
  std::mt19937 rng(5);
  for (const int parts : {1, 2, 5}) {
    CAPTURE(parts);
    std::vector<int> owner(n);
    for (auto& o : owner) o = int(rng() % unsigned(parts));  // scattered: most pairs cross
    CHECK(forces_of_owners(sys, cohesive, owner, parts) == full.force);
  }
}

TEST_CASE("contact kernel: a team whose size changes between steps re-plans its half rows") {
  System sys = random_spheres(2000, 0.65, false, 43);
  ContactParams p;
  const Outcome full = evaluate(sys, p, ContactKernel::kFullRows, 1, {true, true});
  ContactForce contact(p);
  for (const int threads : {2, 1, 3, 2}) {  // no site moves: the list is built once
    CAPTURE(threads);
    const ThreadCountScope scope(threads);
    for (auto& f : sys.sites().force) f = Vec3(0.25, -0.5, 1.0);
    const ForceResult r = contact.add_forces(sys, {true, true});
    CHECK(sys.sites().force == full.force);
    CHECK(r.energy == full.energy);
    CHECK(r.virial == full.virial);
  }
  CHECK(contact.neighbor_list().builds() == 1);
}

TEST_CASE("contact kernel: the slabs of the half rows leave few pairs to compute twice") {
  // Dense spheres, periodic cube of ~13.5 sigma: two slabs cut 2 x 13.5^2 sigma^2; the pairs
  // within the list's reach of a cut are computed by both threads.
  const System sys = random_spheres(2000, 0.65, false, 44);
  ContactParams p;
  CHECK(entries_over_pairs(sys, p, 1) == 1.0);
  const double two = entries_over_pairs(sys, p, 2);
  CHECK(two > 1.0);
  CHECK(two < 1.2);  // a scattered partition: ~1.5
}

TEST_CASE("contact kernel: new parameters (a new list) re-plan the half rows") {
  // Cohesion switched on after one evaluation: the new list's first build must not be taken
  // for the old list's (both are the first build of their list).
  const System start = random_spheres(2000, 0.65, false, 45);
  ContactParams repulsive, cohesive;
  repulsive.skin = 0.05;  // its list lacks the cohesive pairs beyond 1.05 s
  cohesive.beta = 1e-2;
  const Outcome want = evaluate(start, cohesive, ContactKernel::kFullRows, 1, {true, false});
  for (const int threads : {1, 2}) {
    CAPTURE(threads);
    System sys = start;
    const ThreadCountScope scope(threads);
    ContactForce contact(repulsive);
    contact.add_forces(sys, {false, false});
    contact.set_params(cohesive);
    for (auto& f : sys.sites().force) f = Vec3(0.25, -0.5, 1.0);
    const ForceResult r = contact.add_forces(sys, {true, false});
    CHECK(sys.sites().force == want.force);
    CHECK(r.energy == want.energy);
  }
}
