// Reproducibility: trajectories bit-identical across thread counts and repeated runs; the
// Philox generator against Random123's published known-answer vectors; normal deviates;
// thread-count independence of deterministic_sum.
#include <omp.h>
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <set>
#include <vector>

#include "core/deterministic_sum.hpp"
#include "core/parallel.hpp"
#include "core/rng.hpp"
#include "integrate/dynamics.hpp"
#include "test_support.hpp"

using namespace invasim;

namespace {

// Restores the OpenMP thread count when a test ends (even by an exception).
struct ThreadGuard {
  int saved = omp_get_max_threads();
  ~ThreadGuard() { omp_set_num_threads(saved); }
};

// The number of threads an OpenMP parallel region actually gets.
int threads_in_region() {
  int n = 0;
#pragma omp parallel
  {
#pragma omp single
    n = omp_get_num_threads();
  }
  return n;
}

// A copy of `src` (same sites, bodies, positions bit for bit) with another dynamics seed.
System reseeded(const System& src, std::uint64_t seed) {
  System out(src.box(), seed);
  const Sites& s = src.sites();
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.body[i] < 0) out.add_sphere(src.unwrapped(i), s.diameter[i], s.mass[i], s.orient[i]);
  for (std::size_t b = 0; b < src.bodies().size(); ++b) {
    const MeshBody& mb = src.bodies()[b];
    std::vector<Vec3> x(mb.n_vertices());
    src.body_vertices(int(b), x.data());
    out.add_mesh(mb.topology, x, s.diameter[mb.first_site], mb.ref_area, mb.ref_volume,
                 s.mass[mb.first_site]);
  }
  REQUIRE(out.n_sites() == src.n_sites());
  for (std::size_t i = 0; i < s.size(); ++i) REQUIRE(out.sites().body[i] == s.body[i]);
  out.sites().pos = s.pos;
  out.sites().image = s.image;
  return out;
}

struct Snapshot {
  std::vector<Vec3> pos, vel, orient;
  std::vector<Vec3i> image;
  double wall_lo = 0, wall_v = 0;
  std::uint64_t builds = 0;
  std::uint64_t parallel_steps = 0;  // steps run in the parallel team
};

// The mixed system: 8 adipocytes (damped vertices), 700 active cancer cells with
// thermal noise, cohesive contacts, walls, shape, tethers (mean degree 4 plus heterogeneity)
// and a pressure-controlled left wall with its own bath (noise at kT = 1e-3); `steps` steps
// from scratch with `threads` threads, every step in the parallel team when threads > 1 (1036
// sites: at least core/parallel.hpp's kParallelTeamItems).
Snapshot run_mixed(int threads, std::uint64_t dyn_seed, int steps) {
  omp_set_num_threads(threads);
  REQUIRE(threads_in_region() == threads);
  System sys = reseeded(test::mixed_system(2, 700, 7.0, 0.2, 77), dyn_seed);
  REQUIRE(sys.n_sites() >= kParallelTeamItems);
  ForceField ff;
  ContactParams cp;
  cp.beta = 1e-2;
  auto contacts = std::make_shared<ContactForce>(cp);
  auto walls = std::make_shared<WallForce>();
  auto tethers = std::make_shared<TetherForce>(0.5);
  ff.add(contacts);
  ff.add(walls);
  ff.add(std::make_shared<ShapeForce>(100.0, 1.0));
  ff.add(tethers);
  tethers->connect_by_mean_degree(sys, 4.0);
  tethers->apply_heterogeneity(sys, 0.3);
  Dynamics dyn(0.05);
  dyn.step_threads().set_mode(StepThreads::Mode::kAll);
  auto active = Method::active(sys.sites_of_kind(SiteKind::kCancer), 0.2, 0.1, 2.0, 1e-2);
  active->randomize_orientations(sys);
  dyn.add(active);
  dyn.add(Method::damped(sys.sites_of_kind(SiteKind::kVertex), 0.2));
  auto wall = std::make_shared<PressureWall>();
  wall->pressure = 1e-3;
  wall->kT = 1e-3;
  wall->walls = walls;
  dyn.set_pressure_wall(wall);
  dyn.run(sys, ff, steps);
  Snapshot out{sys.sites().pos,
               sys.sites().vel,
               sys.sites().orient,
               sys.sites().image,
               sys.box().lo()[0],
               wall->velocity,
               contacts->neighbor_list().builds()};
  out.parallel_steps = dyn.parallel_steps();
  for (const Vec3& r : out.pos) REQUIRE(r.allFinite());
  return out;
}

// Counts sites whose position, velocity, orientation or image differ in any bit.
std::size_t n_different(const Snapshot& a, const Snapshot& b) {
  REQUIRE(a.pos.size() == b.pos.size());
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.pos.size(); ++i)
    n += !(a.pos[i] == b.pos[i] && a.vel[i] == b.vel[i] && a.orient[i] == b.orient[i] &&
           a.image[i] == b.image[i]);
  return n;
}

}  // namespace

TEST_CASE(
    "trajectories of the full mixed system: bit-identical for 1 and 2 threads and the same seed") {
  ThreadGuard guard;
  const int steps = 1000;
  const Snapshot one = run_mixed(1, 1234, steps);
  const Snapshot two = run_mixed(2, 1234, steps);
  // The run did something: the list rebuilt, the wall moved, the cells were driven.
  CHECK(one.builds > 10);
  CHECK(one.wall_lo != 0.0);
  // The 2-thread run took the parallel team in every step, the 1-thread one never.
  CHECK(two.parallel_steps == std::uint64_t(steps));
  CHECK(one.parallel_steps == 0);
  CHECK(n_different(one, two) == 0);
  CHECK(one.wall_lo == two.wall_lo);
  CHECK(one.wall_v == two.wall_v);
  CHECK(one.builds == two.builds);

  // The same seed twice (from scratch) gives identical results. (One thread here: a
  // 2-thread run costs far more wall time when the machine is shared.)
  const Snapshot again = run_mixed(1, 1234, steps);
  CHECK(n_different(two, again) == 0);
  CHECK(two.wall_lo == again.wall_lo);
  // A different seed from the same start gives a different trajectory.
  const Snapshot other = run_mixed(1, 1235, steps);
  CHECK(n_different(two, other) > two.pos.size() / 2);
  CHECK(two.wall_lo != other.wall_lo);
}

TEST_CASE("philox4x32_10 reproduces Random123's known-answer vectors") {
  using W4 = std::array<std::uint32_t, 4>;
  using W2 = std::array<std::uint32_t, 2>;
  CHECK(philox4x32_10(W4{0, 0, 0, 0}, W2{0, 0}) ==
        W4{0x6627e8d5u, 0xe169c58du, 0xbc57ac4cu, 0x9b00dbd8u});
  CHECK(philox4x32_10(W4{0xffffffffu, 0xffffffffu, 0xffffffffu, 0xffffffffu},
                      W2{0xffffffffu, 0xffffffffu}) ==
        W4{0x408f276du, 0x41c83b0eu, 0xa20bc7c6u, 0x6d5451fdu});
  CHECK(philox4x32_10(W4{0x243f6a88u, 0x85a308d3u, 0x13198a2eu, 0x03707344u},
                      W2{0xa4093822u, 0x299f31d0u}) ==
        W4{0xd16cfe09u, 0x94fdccebu, 0x5001e420u, 0x24126ea1u});
}

TEST_CASE("RandomKey::normal4 is standard normal over 1e6 draws (5-sigma tolerances)") {
  const int keys = 250000;  // x 4 = 1e6 draws
  double sum = 0, sum2 = 0, sum4 = 0, cross01 = 0, cross23 = 0, cross02 = 0;
  double comp_sum[4] = {0, 0, 0, 0};
  double umin = 1, umax = 0;
  for (int k = 0; k < keys; ++k) {
    const RandomKey key(99, std::uint64_t(k / 1000), std::uint32_t(k % 1000), RngStream::kThermal);
    const auto g = key.normal4();
    for (int c = 0; c < 4; ++c) {
      sum += g[c];
      sum2 += g[c] * g[c];
      sum4 += g[c] * g[c] * g[c] * g[c];
      comp_sum[c] += g[c];
    }
    cross01 += g[0] * g[1];
    cross23 += g[2] * g[3];
    cross02 += g[0] * g[2];
    for (double u : key.uniform4()) {
      umin = std::min(umin, u);
      umax = std::max(umax, u);
    }
  }
  const double n = 4.0 * keys;
  const double mean = sum / n, var = sum2 / n - mean * mean, m4 = sum4 / n;
  // Standard errors: mean 1/sqrt(n); variance sqrt(2/n); 4th moment sqrt(96/n);
  // a component mean or a product moment 1/sqrt(keys).
  CHECK(std::abs(mean) < 5.0 / std::sqrt(n));
  CHECK(std::abs(var - 1.0) < 5.0 * std::sqrt(2.0 / n));
  CHECK(std::abs(m4 - 3.0) < 5.0 * std::sqrt(96.0 / n));
  for (double c : comp_sum) CHECK(std::abs(c / keys) < 5.0 / std::sqrt(double(keys)));
  CHECK(std::abs(cross01 / keys) < 5.0 / std::sqrt(double(keys)));
  CHECK(std::abs(cross23 / keys) < 5.0 / std::sqrt(double(keys)));
  CHECK(std::abs(cross02 / keys) < 5.0 / std::sqrt(double(keys)));
  CHECK(umin > 0.0);
  CHECK(umax < 1.0);
}

TEST_CASE(
    "RandomKey::normal3 (ziggurat) is standard normal over 3e6 draws: moments, CDF, tail, "
    "independent components (5-sigma tolerances)") {
  const int keys = 1000000;  // x 3 = 3e6 draws
  const double cuts[] = {-3.0, -2.0, -1.5, -1.0, -0.5, -0.2, 0.0, 0.2, 0.5, 1.0, 1.5, 2.0, 3.0};
  constexpr int n_cuts = sizeof(cuts) / sizeof(cuts[0]);
  long below[n_cuts] = {};
  long tail = 0;  // |x| > r: drawn by the ziggurat's tail method
  long impure = 0;
  double sum = 0, sum2 = 0, sum3 = 0, sum4 = 0, cross01 = 0, cross12 = 0, cross02 = 0;
  for (int k = 0; k < keys; ++k) {
    const RandomKey key(2024, std::uint64_t(k / 1000), std::uint32_t(k % 1000),
                        RngStream::kThermal);
    const Vec3 g = key.normal3();
    impure += !(g == key.normal3());  // a pure function of the key
    for (int c = 0; c < 3; ++c) {
      const double x = g[c];
      sum += x;
      sum2 += x * x;
      sum3 += x * x * x;
      sum4 += x * x * x * x;
      for (int q = 0; q < n_cuts; ++q) below[q] += x < cuts[q];
      tail += std::abs(x) > ZigguratTables::kR;
    }
    cross01 += g[0] * g[1];
    cross12 += g[1] * g[2];
    cross02 += g[0] * g[2];
  }
  const double n = 3.0 * keys;
  CHECK(impure == 0);
  CHECK(std::abs(sum / n) < 5.0 / std::sqrt(n));
  CHECK(std::abs(sum2 / n - 1.0) < 5.0 * std::sqrt(2.0 / n));
  CHECK(std::abs(sum3 / n) < 5.0 * std::sqrt(15.0 / n));
  CHECK(std::abs(sum4 / n - 3.0) < 5.0 * std::sqrt(96.0 / n));
  for (double c : {cross01, cross12, cross02})
    CHECK(std::abs(c / keys) < 5.0 / std::sqrt(double(keys)));
  for (int q = 0; q < n_cuts; ++q) {
    const double p = 0.5 * std::erfc(-cuts[q] / std::sqrt(2.0));
    CAPTURE(cuts[q], below[q] / n, p);
    CHECK(std::abs(below[q] / n - p) < 5.0 * std::sqrt(p * (1 - p) / n));
  }
  const double p_tail = std::erfc(ZigguratTables::kR / std::sqrt(2.0));
  CHECK(tail > 0);
  CHECK(std::abs(tail / n - p_tail) < 5.0 * std::sqrt(p_tail / n));
}

TEST_CASE("RandomKey::normal3_batch gives normal3's numbers bit for bit, rejections included") {
  // 2e5 keys in batches of every size from 1 to kBatch over scattered site indices: ~16000
  // components (2.8 %) take the ziggurat's slow path (wedges and tail), in normal3's order.
  constexpr int B = RandomKey::kBatch;
  std::vector<int> sites(B);
  double g[3][B];
  long compared = 0, mismatched = 0, slow = 0, tail = 0;
  const ZigguratTables& z = ziggurat_tables();
  for (std::uint64_t step = 0; compared < 600000; ++step) {
    const int m = 1 + int(step % B);
    for (int q = 0; q < m; ++q) sites[q] = int((step * 7919 + std::uint64_t(q) * 104729) % 100000);
    RandomKey::normal3_batch(99, step, sites.data(), m, RngStream::kThermal, g);
    for (int q = 0; q < m; ++q) {
      const RandomKey key(99, step, std::uint32_t(sites[q]), RngStream::kThermal);
      const Vec3 ref = key.normal3();
      const auto w =
          philox4x32_10({std::uint32_t(step), std::uint32_t(step >> 32), std::uint32_t(sites[q]),
                         std::uint32_t(RngStream::kThermal) << 16},
                        {99u, 0u});
      for (int c = 0; c < 3; ++c) {
        ++compared;
        mismatched += !(g[c][q] == ref[c]);
        const double u = (double(std::int32_t(w[c])) + 0.5) * 0x1p-31;
        slow += !(std::abs(u) < z.ratio[int(w[3] >> (7 * c)) & (ZigguratTables::kLayers - 1)]);
        tail += std::abs(ref[c]) > ZigguratTables::kR;
      }
    }
  }
  INFO(compared << " components, " << slow << " on the slow path, " << tail << " in the tail");
  CHECK(mismatched == 0);
  CHECK(slow > 1000);
  CHECK(tail > 0);
}

TEST_CASE("different seeds, steps, sites, streams and sub-streams give different numbers") {
  const auto base = RandomKey(7, 100, 5, RngStream::kThermal).uniform4();
  // Same key: same numbers.
  CHECK(RandomKey(7, 100, 5, RngStream::kThermal).uniform4() == base);
  const std::vector<std::array<double, 4>> variants = {
      RandomKey(8, 100, 5, RngStream::kThermal).uniform4(),
      RandomKey(7 + (std::uint64_t(1) << 32), 100, 5, RngStream::kThermal).uniform4(),
      RandomKey(7, 101, 5, RngStream::kThermal).uniform4(),
      RandomKey(7, 100 + (std::uint64_t(1) << 32), 5, RngStream::kThermal).uniform4(),
      RandomKey(7, 100, 6, RngStream::kThermal).uniform4(),
      RandomKey(7, 100, 5, RngStream::kOrientation).uniform4(),
      RandomKey(7, 100, 5, RngStream::kPlacement).uniform4(),
      RandomKey(7, 100, 5, RngStream::kThermal, 1).uniform4(),
  };
  std::set<double> seen(base.begin(), base.end());
  for (const auto& v : variants) {
    CHECK(v != base);
    seen.insert(v.begin(), v.end());
  }
  // Every one of the 36 numbers is distinct.
  CHECK(seen.size() == 4 * (variants.size() + 1));
  // Site and step must not alias: (step 1, site 0) differs from (step 0, site 1).
  CHECK(RandomKey(7, 1, 0, RngStream::kThermal).uniform4() !=
        RandomKey(7, 0, 1, RngStream::kThermal).uniform4());
}

TEST_CASE("deterministic_sum gives the same bits with 1 and 2 threads") {
  ThreadGuard guard;
  // Values spanning 20 orders of magnitude with both signs: any change of summation order
  // changes the rounding of the result.
  const std::size_t n = 200003;
  std::vector<double> x(n);
  std::vector<Vec3> v(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto u = RandomKey(3, 0, std::uint32_t(i), RngStream::kUser).uniform4();
    x[i] = (u[0] - 0.5) * std::pow(10.0, 20.0 * u[1] - 10.0);
    v[i] = Vec3(x[i], u[2] - 0.5, std::pow(10.0, 8.0 * u[3]) * (u[0] - 0.5));
  }
  // The reference: blocks of kSumBlock summed in order, then the block sums in order.
  double ref = 0.0;
  Vec3 vref = Vec3::Zero();
  for (std::size_t b = 0; b * kSumBlock < n; ++b) {
    double s = 0.0;
    Vec3 sv = Vec3::Zero();
    for (std::size_t i = b * kSumBlock; i < std::min(n, (b + 1) * kSumBlock); ++i) {
      s += x[i];
      sv += v[i];
    }
    ref += s;
    vref += sv;
  }
  // The plain sequential sum rounds differently (so bit equality below is a real test).
  double plain = 0.0;
  for (double xi : x) plain += xi;
  CHECK(plain != ref);
  for (int threads : {1, 2}) {
    omp_set_num_threads(threads);
    REQUIRE(threads_in_region() == threads);
    const double s = deterministic_sum(n, 0.0, [&](std::size_t i) { return x[i]; });
    const Vec3 sv = deterministic_sum(n, Vec3(Vec3::Zero()), [&](std::size_t i) { return v[i]; });
    CHECK(s == ref);
    CHECK(sv == vref);
  }
  // Empty and single-element sums.
  CHECK(deterministic_sum(0, 0.0, [&](std::size_t i) { return x[i]; }) == 0.0);
  CHECK(deterministic_sum(1, 0.0, [&](std::size_t i) { return x[i]; }) == x[0]);
}
