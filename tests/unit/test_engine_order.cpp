// The engine order (integrate/engine_order.hpp, System's storage layouts): Dynamics' steps store
// the sites spatially sorted and give them back in the user's order; the order is part of the
// state that a checkpoint keeps, the random numbers follow the sites' permanent indices, and the
// results stay independent of the thread count across changes of the order.
#include <omp.h>
#include <catch2/catch.hpp>

#include <algorithm>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <vector>

#include "checkpoint/state_checkpoint.hpp"
#include "core/parallel.hpp"
#include "integrate/dynamics.hpp"
#include "integrate/engine_order.hpp"
#include "integrate/fire.hpp"
#include "test_support.hpp"

using namespace invasim;
using Catch::Matchers::Contains;

namespace {

struct ThreadGuard {
  int saved = omp_get_max_threads();
  ~ThreadGuard() { omp_set_num_threads(saved); }
};

// Adipocytes and active, thermal cells with contacts (cohesive), walls and shape forces, the
// engine order chosen again every 8 steps.
struct Tissue {
  explicit Tissue(System s) : sys(std::move(s)), ff(test::standard_forces(1e-2)) {}
  System sys;
  ForceField ff;
  Dynamics dyn{0.05};
};

// (restored: the System comes from a checkpoint, with its orientations.)
std::unique_ptr<Tissue> make_tissue(System sys, bool restored = false) {
  auto t = std::make_unique<Tissue>(std::move(sys));
  auto cells = Method::active(t->sys.sites_of_kind(SiteKind::kCancer), 0.2, 0.3, 2.0, 1e-2);
  if (!restored) cells->randomize_orientations(t->sys);
  t->dyn.add(cells);
  t->dyn.add(Method::damped(t->sys.sites_of_kind(SiteKind::kVertex), 0.2));
  t->dyn.set_sort_every(8);
  return t;
}

// A dense tissue (cells at packing fraction 0.6 beside 8 adipocytes, relaxed): many sites with
// three contacts or more, whose force sums depend on the order of their terms; 1036 sites, so
// that a step at 2 threads runs in the parallel team (core/parallel.hpp, kParallelTeamItems).
System start() {
  static const System relaxed = [] {
    System sys = test::slab_system(2, 2, 700, 5.2, 0.6, 11);
    REQUIRE(sys.n_sites() >= kParallelTeamItems);
    ForceField ff = test::standard_forces(1e-2);
    FireParams fp;
    fp.ftol = 1e-3;
    fp.max_steps = 300;
    Fire(fp).minimize(sys, ff);
    return sys;
  }();
  return relaxed;
}

bool identical(const System& a, const System& b) {
  const Sites &s = a.sites(), &t = b.sites();
  return s.pos == t.pos && s.vel == t.vel && s.force == t.force && s.orient == t.orient &&
         s.image == t.image && s.diameter == t.diameter && s.mass == t.mass && s.body == t.body &&
         s.kind == t.kind && a.step == b.step && a.engine_order() == b.engine_order();
}

bool is_identity(const std::vector<int>& order) {
  for (std::size_t k = 0; k < order.size(); ++k)
    if (order[k] != int(k)) return false;
  return true;
}

}  // namespace

TEST_CASE(
    "engine order: sorted by kind, a permutation, after a run the sites are in the user's "
    "order") {
  const System initial = start();
  auto t = make_tissue(start());
  t->dyn.run(t->sys, t->ff, 40);  // the order chosen at steps 0, 8, ..., 32
  const System& sys = t->sys;
  REQUIRE_FALSE(sys.engine_layout());
  CHECK(sys.layout_id() == 0);
  const std::vector<int>& order = sys.engine_order();
  REQUIRE(order.size() == sys.n_sites());
  std::vector<int> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  std::vector<int> identity(sys.n_sites());
  std::iota(identity.begin(), identity.end(), 0);
  CHECK(sorted == identity);
  CHECK_FALSE(is_identity(order));
  // Kind-major: every cancer cell before every vertex.
  for (std::size_t k = 1; k < order.size(); ++k)
    CHECK(int(initial.sites().kind[order[k - 1]]) <= int(initial.sites().kind[order[k]]));
  // Each site is back at its permanent index: the per-site constants as created, and the same
  // run with the order chosen once (at step 0) instead of 5 times puts every site within
  // rounding of the same place (the orders change only the summation order), though the sites
  // moved by about a diameter.
  const Sites &s = sys.sites(), &s0 = initial.sites();
  CHECK(s.kind == s0.kind);
  CHECK(s.diameter == s0.diameter);
  CHECK(s.mass == s0.mass);
  CHECK(s.body == s0.body);
  CHECK(sys.sites_of_kind(SiteKind::kCancer) == initial.sites_of_kind(SiteKind::kCancer));
  auto once = make_tissue(start());
  once->dyn.set_sort_every(1000);
  once->dyn.run(once->sys, once->ff, 40);
  double moved = 0.0, differ = 0.0;
  for (std::size_t i = 0; i < sys.n_sites(); ++i) {
    moved = std::max(moved, sys.box().minimum_image(s.pos[i] - s0.pos[i]).norm());
    differ = std::max(differ, (once->sys.sites().pos[i] - s.pos[i]).norm());
    differ = std::max(differ, (once->sys.sites().orient[i] - s.orient[i]).norm());
  }
  CHECK(moved > 0.5);
  CHECK(differ < 1e-8);
  CHECK(once->sys.engine_order() != sys.engine_order());
}

TEST_CASE("engine order: the spatial sort makes index ranges slabs, and the layouts round-trip") {
  System sys = start();
  const System copy = sys;
  {
    const EngineLayoutScope layout(sys);
    REQUIRE(sys.engine_layout());
    CHECK(sys.layout_id() != 0);
    // Slot k holds site engine_order()[k]; slot_of inverts it.
    for (std::size_t k = 0; k < sys.n_sites(); ++k) {
      const int i = sys.engine_order()[k];
      CHECK(sys.site_of_slot(int(k)) == i);
      CHECK(sys.slot_of(i) == int(k));
      CHECK(sys.sites().pos[k] == copy.sites().pos[i]);
    }
    // The cancer cells' slots, in halves, lie in two slabs along the slab axis (the grid's
    // slowest axis): at most one grid cell's width of overlap between the halves.
    const int axis = slab_axis(sys, 2);
    const auto cells = sys.sites_of_kind(SiteKind::kCancer);
    std::vector<double> x;
    for (std::size_t k = 0; k < cells.size(); ++k) x.push_back(sys.sites().pos[k][axis]);
    const std::size_t half = x.size() / 2;
    const double first_max = *std::max_element(x.begin(), x.begin() + half);
    const double second_min = *std::min_element(x.begin() + half, x.end());
    CHECK(first_max < second_min + 2.2);  // (cells at most twice the largest diameter wide)
    // Adding a site in the engine layout is refused.
    CHECK_THROWS_AS(sys.add_sphere(Vec3(1.0, 1.0, 1.0), 1.0), std::logic_error);
    // A new order in the engine layout moves the sites at once.
    std::vector<int> reversed(sys.engine_order().rbegin(), sys.engine_order().rend());
    sys.set_engine_order(reversed);
    CHECK(sys.sites().pos.front() == copy.sites().pos[reversed.front()]);
  }
  CHECK_FALSE(sys.engine_layout());
  CHECK(sys.sites().pos == copy.sites().pos);
  CHECK(sys.sites().kind == copy.sites().kind);
  CHECK_THROWS_WITH(sys.set_engine_order({0, 1}), Contains("entries for"));
  std::vector<int> twice(sys.n_sites(), 0);
  CHECK_THROWS_WITH(sys.set_engine_order(twice), Contains("must be a permutation"));
  // Adding a site drops the order (the next run chooses one for the new set of sites).
  sys.add_sphere(Vec3(1.0, 1.0, 1.0), 1.0);
  CHECK(sys.engine_order().empty());
}

TEST_CASE(
    "engine order: a run restored from a checkpoint between two changes of the order "
    "continues bit for bit") {
  ThreadGuard guard;
  omp_set_num_threads(2);
  // Every step in the parallel team (the restored order must hold for its sums too).
  auto team = [](std::unique_ptr<Tissue> t) {
    t->dyn.step_threads().set_mode(StepThreads::Mode::kAll);
    return t;
  };
  auto straight = team(make_tissue(start()));
  straight->dyn.run(straight->sys, straight->ff, 45);
  CHECK(straight->dyn.parallel_steps() == 45);

  auto first = team(make_tissue(start()));
  first->dyn.run(first->sys, first->ff, 21);  // the order of step 16 in use
  CheckpointWriter w;
  write_system(w, first->sys);
  const CheckpointReader r = CheckpointReader::parse(w.bytes(), "'test'");
  auto second = team(make_tissue(read_system(r), true));
  REQUIRE(second->sys.engine_order() == first->sys.engine_order());
  // The order chosen now would differ: the restored one is what keeps the sums' order.
  REQUIRE(spatial_order(second->sys) != second->sys.engine_order());
  second->dyn.mark_prepared();  // the forces of step 21, as stored
  second->dyn.run(second->sys, second->ff, 24);
  first->dyn.run(first->sys, first->ff, 24);
  CHECK(identical(first->sys, straight->sys));
  CHECK(identical(second->sys, straight->sys));
  CHECK(second->dyn.parallel_steps() == 24);
}

TEST_CASE("engine order: 1 and 2 threads give the same bits across changes of the order") {
  ThreadGuard guard;
  omp_set_num_threads(1);
  auto one = make_tissue(start());
  one->dyn.run(one->sys, one->ff, 45);
  omp_set_num_threads(2);
  auto two = make_tissue(start());
  two->dyn.step_threads().set_mode(StepThreads::Mode::kAll);
  two->dyn.run(two->sys, two->ff, 45);
  CHECK(two->dyn.step_threads().team_steps() == 45);
  CHECK(two->dyn.parallel_steps() == 45);  // run in the team, not only chosen for it
  CHECK(one->dyn.parallel_steps() == 0);
  CHECK(identical(one->sys, two->sys));
}

TEST_CASE(
    "engine order: the thermal noise follows the sites' permanent indices, not their "
    "slots") {
  // Free Langevin particles (no forces: each site's update is its own arithmetic and its own
  // random numbers), ordered once and ordered again at every step: the same bits.
  auto run = [](std::uint64_t sort_every) {
    System sys = test::free_particles(500, 1.0, 5);
    ForceField ff;
    Dynamics dyn(0.05);
    dyn.add(Method::langevin(test::all_sites(sys), 0.2, 1e-2));
    dyn.set_sort_every(sort_every);
    for (int k = 0; k < 5; ++k) dyn.run(sys, ff, 20);
    return sys;
  };
  const System rarely = run(1000), always = run(1);
  CHECK(rarely.sites().pos == always.sites().pos);
  CHECK(rarely.sites().vel == always.sites().vel);
  CHECK(rarely.engine_order() != always.engine_order());
}
