// Dilute random placement, packing fractions, compression to a target phi and rescaling.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "checkpoint/state_checkpoint.hpp"
#include "core/errors.hpp"
#include "integrate/fire.hpp"
#include "mesh/geometry.hpp"
#include "setup/compression.hpp"
#include "setup/placement.hpp"
#include "test_support.hpp"

using namespace invasim;
using Catch::Matchers::Contains;

namespace {

// The paper's de-mixed start scaled to n_a adipocytes and n_c cells at phi0 = 0.01: x ranges
// (2, 12) for cells and (16, 68) for adipocyte centres in a box of L0 = 70, scaled with L0.
// With `mixed` the cells are spread over the whole box instead (a negative control).
System dilute_start(int n_a, int n_c, std::uint64_t seed, PlacementResult* placed = nullptr,
                    bool mixed = false) {
  const double v_cells = n_c * M_PI / 6.0 * 0.5 * (0.9 * 0.9 * 0.9 + 1.1 * 1.1 * 1.1);
  const MeshShape shape = icosphere(1);
  std::vector<Vec3> x;
  for (const Vec3& v : shape.vertices) x.push_back(2.0 * v);
  const double v_body = union_volume(*shape.topology, x.data(), 2.0, 0.05);
  const double L0 = std::cbrt((v_cells + n_a * v_body) / 0.01);
  System sys(Box(Vec3::Zero(), Vec3::Constant(L0), {false, true, true}), seed);
  MeshPlacement mp;
  mp.n = n_a;
  mp.x = {16.0 / 70.0 * L0, 68.0 / 70.0 * L0 - 3.0};
  SpherePlacement sp;
  sp.n = n_c;
  sp.x = {2.0 / 70.0 * L0, (mixed ? 68.0 : 12.0) / 70.0 * L0};
  const PlacementResult r = place_random(sys, mp, sp);
  if (placed) *placed = r;
  return sys;
}

double min_pair_gap(const System& sys) {
  // Smallest surface gap between any two sites of different bodies (brute force).
  const Sites& s = sys.sites();
  double gap = 1e300;
  for (std::size_t i = 0; i < s.size(); ++i)
    for (std::size_t j = i + 1; j < s.size(); ++j) {
      if (s.body[i] >= 0 && s.body[i] == s.body[j]) continue;
      const double r = sys.box().minimum_image(s.pos[i] - s.pos[j]).norm();
      gap = std::min(gap, r - 0.5 * (s.diameter[i] + s.diameter[j]));
    }
  return gap;
}

}  // namespace

TEST_CASE("random placement is de-mixed, overlap-free, reproducible and sets V_i") {
  PlacementResult placed;
  const System sys = dilute_start(6, 300, 3, &placed);
  CHECK(placed.cells.size() == 300);
  CHECK(placed.bodies.size() == 6);
  CHECK(min_pair_gap(sys) >= 0.0);
  const double L0 = sys.box().length(0);
  for (int i : placed.cells) {
    CHECK(sys.sites().pos[i][0] >= 2.0 / 70.0 * L0);
    CHECK(sys.sites().pos[i][0] <= 12.0 / 70.0 * L0);
  }
  std::vector<Vec3> x(42);
  for (int b : placed.bodies) {
    sys.body_vertices(b, x.data());
    CHECK(vertex_centroid(42, x.data())[0] >= 16.0 / 70.0 * L0 - 1e-9);
    // V_i of a radius-2 icosphere with vertex diameter 2 lies between the mesh volume + the
    // outside caps and the ball of radius 3.
    CHECK(sys.bodies()[b].outer_volume > 80.0);
    CHECK(sys.bodies()[b].outer_volume < 4.0 / 3.0 * M_PI * 27.0);
  }
  CHECK(packing_fractions(sys).total == Approx(0.01).epsilon(1e-12));
  const System again = dilute_start(6, 300, 3);
  CHECK(again.sites().pos == sys.sites().pos);
  const System other = dilute_start(6, 300, 4);
  CHECK(other.sites().pos != sys.sites().pos);
}

namespace {
// The outer diameters of the placed bodies from their meshes: the icosphere's vertices lie at
// the mesh radius from its centre, plus the vertex radius.
std::vector<double> diameters(const System& sys, const PlacementResult& r, double vertex_diameter) {
  std::vector<double> d;
  std::vector<Vec3> x(42);
  for (int b : r.bodies) {
    sys.body_vertices(b, x.data());
    const Vec3 c = vertex_centroid(42, x.data());
    d.push_back(2.0 * (x[0] - c).norm() + vertex_diameter);
  }
  return d;
}
}  // namespace

TEST_CASE("adipocytes of many sizes: log-normal diameters of the given mean, or a list in turn") {
  const double L = 120.0;
  MeshPlacement mp;
  mp.n = 300;
  mp.x = {5.0, L - 5.0};
  mp.spread = 0.2;
  System sys(Box(Vec3::Zero(), Vec3::Constant(L), {false, true, true}), 5);
  const PlacementResult r = place_random(sys, mp, SpherePlacement{});
  REQUIRE(r.bodies.size() == 300);
  const std::vector<double> d = diameters(sys, r, mp.vertex_diameter);
  double mean = 0.0, mean_log = 0.0;
  for (double v : d) mean += v / double(d.size());
  for (double v : d) mean_log += std::log(v) / double(d.size());
  double var = 0.0, var_log = 0.0;
  for (double v : d) var += (v - mean) * (v - mean) / double(d.size() - 1);
  for (double v : d)
    var_log += (std::log(v) - mean_log) * (std::log(v) - mean_log) / double(d.size() - 1);
  // Mean 6 (the given diameter), log spread 0.2: within 3 standard errors.
  CHECK(std::abs(mean - 6.0) < 3.0 * std::sqrt(var / double(d.size())));
  CHECK(std::abs(std::sqrt(var_log) - 0.2) < 3.0 * 0.2 / std::sqrt(2.0 * double(d.size())));
  // Each body's reference volume and V_i belong to its own size: the reference volume
  // scales as the mesh radius cubed.
  const MeshBody& first = sys.bodies()[std::size_t(r.bodies[0])];
  for (std::size_t k = 1; k < r.bodies.size(); ++k) {
    const MeshBody& body = sys.bodies()[std::size_t(r.bodies[k])];
    const double ratio = (d[k] - 2.0) / (d[0] - 2.0);
    CHECK(body.ref_volume == Approx(first.ref_volume * ratio * ratio * ratio).epsilon(1e-9));
    CHECK((body.outer_volume > first.outer_volume) == (d[k] > d[0]));
  }
  CHECK(min_pair_gap(sys) >= 0.0);
  // The same seed gives the same sizes; no spread, one size.
  System again(Box(Vec3::Zero(), Vec3::Constant(L), {false, true, true}), 5);
  CHECK(diameters(again, place_random(again, mp, SpherePlacement{}), 2.0) == d);
  // A list: the k-th adipocyte gets diameters[k % size].
  MeshPlacement listed;
  listed.n = 5;
  listed.x = {10.0, L - 10.0};
  listed.diameters = {5.0, 8.0};
  System sys2(Box(Vec3::Zero(), Vec3::Constant(L), {false, true, true}), 6);
  const std::vector<double> d2 =
      diameters(sys2, place_random(sys2, listed, SpherePlacement{}), listed.vertex_diameter);
  REQUIRE(d2.size() == 5);
  for (std::size_t k = 0; k < 5; ++k) CHECK(d2[k] == Approx(k % 2 ? 8.0 : 5.0).epsilon(1e-12));
  // Refused: a list and a spread together; a size not above the vertex diameter.
  listed.spread = 0.1;
  CHECK_THROWS_WITH(place_random(sys2, listed, SpherePlacement{}),
                    Contains("as a list or as a spread, not both"));
  listed.spread = 0.0;
  listed.diameters = {6.0, 1.5};
  CHECK_THROWS_WITH(place_random(sys2, listed, SpherePlacement{}),
                    Contains("adipocyte 1: diameter = 1.5 must exceed the vertex diameter = 2"));
}

TEST_CASE("log-normal adipocyte diameters: the mean is the given diameter, the log mean below it") {
  // d = D exp(s z - s^2 / 2), z standard normal: E[d] = D and E[ln d] = ln D - s^2 / 2. 2000
  // bodies (a coarse volume grid: V_i is not looked at) resolve the s^2 / 2 = 0.02 that a
  // law without it would add to both, by 4.5 standard errors.
  MeshPlacement mp;
  mp.n = 2000;
  mp.x = {5.0, 155.0};
  mp.spread = 0.2;
  mp.volume_grid = 1.0;
  System sys(Box(Vec3::Zero(), Vec3::Constant(160.0), {false, true, true}), 8);
  const PlacementResult r = place_random(sys, mp, SpherePlacement{});
  const std::vector<double> d = diameters(sys, r, mp.vertex_diameter);
  REQUIRE(d.size() == 2000);
  double mean = 0.0, mean_log = 0.0;
  for (double v : d) mean += v / double(d.size());
  for (double v : d) mean_log += std::log(v) / double(d.size());
  const double n = double(d.size()), s = mp.spread;
  const double se = 6.0 * std::sqrt(std::expm1(s * s) / n), se_log = s / std::sqrt(n);
  INFO("mean " << mean << " +- " << se << ", log mean " << mean_log << " +- " << se_log);
  CHECK(std::abs(mean - 6.0) < 3.0 * se);
  CHECK(std::abs(mean_log - (std::log(6.0) - 0.5 * s * s)) < 3.0 * se_log);
}

TEST_CASE("placement refuses regions that cannot hold the bodies, naming the region") {
  System sys(Box(Vec3::Zero(), Vec3::Constant(10.0), {false, true, true}), 1);
  SpherePlacement sp;
  sp.n = 5000;
  sp.x = {1.0, 2.0};
  sp.max_attempts_per_cell = 200;
  CHECK_THROWS_WITH(place_random(sys, MeshPlacement{}, sp),
                    Contains("cells fit in x range [1, 2]"));
  CHECK(sys.n_sites() == 0);  // the cells that fitted before the failure are not kept
  MeshPlacement mp;
  mp.n = 30;
  mp.x = {3.0, 7.0};
  mp.max_attempts_per_body = 50;
  CHECK_THROWS_WITH(place_random(sys, mp, SpherePlacement{}), Contains("adipocytes fit"));
  CHECK(sys.n_sites() == 0);
  CHECK(sys.bodies().empty());
  sp.x = {-5.0, 2.0};
  CHECK_THROWS_WITH(place_random(sys, MeshPlacement{}, sp),
                    Contains("does not fit between the walls"));
}

// A start from another program: cells where they are given, overlapping or not.
TEST_CASE("placement at given positions: as given (wrapped, unwrapped kept), diameters in turn") {
  System sys(Box(Vec3::Zero(), Vec3::Constant(10.0), {false, true, true}), 1);
  SpherePlacement sp;
  sp.positions = {Vec3(1.0, 2.0, 3.0), Vec3(1.2, 2.0, 3.0), Vec3(9.0, 12.5, -0.5)};
  sp.n = 3;
  const PlacementResult r = place_random(sys, MeshPlacement{}, sp);
  REQUIRE(r.cells == std::vector<int>{0, 1, 2});
  CHECK(sys.sites().pos[1] == Vec3(1.2, 2.0, 3.0));  // overlapping its neighbour: kept
  CHECK(sys.sites().pos[2].isApprox(Vec3(9.0, 2.5, 9.5)));
  CHECK(sys.unwrapped(2).isApprox(Vec3(9.0, 12.5, -0.5)));
  CHECK(sys.sites().diameter == std::vector<double>{0.9, 1.1, 0.9});
  sp.n = 2;
  CHECK_THROWS_WITH(place_random(sys, MeshPlacement{}, sp),
                    Contains("n = 2 for 3 given positions"));
  sp.n = 2;
  sp.positions = {Vec3(5.0, 1.0, 1.0), Vec3(10.5, 1.0, 1.0)};
  CHECK_THROWS_WITH(place_random(sys, MeshPlacement{}, sp),
                    Contains("position 2 has x = 10.5, outside the walls [0, 10]"));
  CHECK(sys.n_sites() == 3);  // nothing added
}

// protocols/cells_only.lua: cells over the whole of a box periodic in x, no walls.
TEST_CASE("placement in a box periodic in x spans the whole box without overlaps") {
  System sys(Box(Vec3::Zero(), Vec3::Constant(12.0), {true, true, true}), 2);
  SpherePlacement sp;
  sp.n = 300;  // phi = 0.18
  sp.x = {0.0, 12.0};
  const PlacementResult r = place_random(sys, MeshPlacement{}, sp);
  REQUIRE(r.cells.size() == 300);
  CHECK(min_pair_gap(sys) >= 0.0);
  double x_min = 1e300, x_max = -1e300;
  for (int i : r.cells) {
    x_min = std::min(x_min, sys.sites().pos[i][0]);
    x_max = std::max(x_max, sys.sites().pos[i][0]);
  }
  CHECK(x_min < 0.45);  // closer to the periodic edges than a wall would allow
  CHECK(x_max > 11.55);
  sp.x = {-1.0, 12.0};
  CHECK_THROWS_WITH(place_random(sys, MeshPlacement{}, sp),
                    Contains("is outside the periodic box [0, 12]"));
}

namespace {

// How de-mixed the cancer cells and adipocytes are (see demixing).
struct Demixing {
  double mean_cell_x = 0.0;           // mean x of the cancer cells
  double leftmost_centre_x = 1e300;   // smallest x of an adipocyte's vertex centroid
  int cell = -1;                      // the cell closest to lying behind an adipocyte,
  double cell_x = 0.0, body_x = 0.0;  // its x and that adipocyte's centre x,
  double yz_distance = 1e300;         // and their periodic y-z distance
};

// De-mixed with a planar interface means the cells fill a slab at the left wall (their mean
// x is left of every adipocyte centre) whose surface follows the first layer of adipocytes:
// cells may fill the grooves between adipocytes, whose depth is about one adipocyte radius,
// but none may sit behind one. A cell counts as behind adipocyte b when b's centre is left of
// it (smaller x) and within half the outer radius (1.5 sigma) of it in the periodic y-z
// plane, i.e. well inside b's shadow on the wall: to get there the cell would have passed
// through the adipocyte layer. A cell in a groove between two or three touching adipocytes
// stays about one outer radius (2.5-3 sigma) from their centres in y-z; a mixed packing has
// cells deep in the tissue, most of them behind several.
Demixing demixing(const System& sys) {
  Demixing m;
  std::vector<Vec3> x(42), centres;
  for (std::size_t b = 0; b < sys.bodies().size(); ++b) {
    sys.body_vertices(int(b), x.data());
    centres.push_back(vertex_centroid(42, x.data()));
    m.leftmost_centre_x = std::min(m.leftmost_centre_x, centres.back()[0]);
  }
  const std::vector<int> cells = sys.sites_of_kind(SiteKind::kCancer);
  for (int i : cells) {
    const Vec3& r = sys.sites().pos[i];
    m.mean_cell_x += r[0] / double(cells.size());
    for (const Vec3& c : centres) {
      if (c[0] >= r[0]) continue;
      const Vec3 d = sys.box().minimum_image(r - c);
      const double yz = std::hypot(d[1], d[2]);
      if (yz < m.yz_distance) {
        m.cell = i;
        m.cell_x = r[0];
        m.body_x = c[0];
        m.yz_distance = yz;
      }
    }
  }
  return m;
}

// Compresses a dilute de-mixed start to phi = 0.72 with FIRE to `ftol` after every 3 % step,
// then minimises to `final_ftol` (the protocol's compress stage), and checks: every
// minimisation converged, phi within 1e-3, the final max force below final_ftol, the number
// of steps, adipocyte volumes within 1 %, and a de-mixed packing (see demixing). With
// `max_iterations` > 0, also that all FIRE iterations together stay below it; `dt_max` is
// FIRE's largest time step (default: the engine's).
void check_compression(int n_a, int n_c, double ftol, double final_ftol,
                       double dt_max = FireParams{}.dt_max, std::uint64_t max_iterations = 0) {
  System sys = dilute_start(n_a, n_c, 5);
  const double phi0 = packing_fractions(sys).total;
  ForceField ff = test::standard_forces(0.0, 1e3, 1.0);
  CompressionParams cp;
  cp.target_phi = 0.72;
  cp.fire.ftol = ftol;
  cp.fire.max_steps = 1000000;
  cp.fire.dt_max = dt_max;
  const CompressionReport r = compress_to_phi(sys, ff, cp);
  FireParams final_fire = cp.fire;
  final_fire.ftol = final_ftol;
  const FireResult f = Fire(final_fire).minimize(sys, ff);
  INFO("steps " << r.steps << ", FIRE steps " << r.fire_steps << " + " << f.steps
                << ", L = " << r.box_lengths.transpose());
  CHECK(r.converged);
  CHECK(f.converged);
  CHECK(std::abs(packing_fractions(sys).total - 0.72) < 1e-3);
  CHECK(f.max_force < final_ftol);
  CHECK(r.steps == std::size_t(std::ceil(std::log(0.72 / phi0) / std::log(1.03))));
  if (max_iterations > 0) CHECK(r.fire_steps + f.steps < max_iterations);
  std::vector<Vec3> x(42);
  for (std::size_t b = 0; b < sys.bodies().size(); ++b) {
    sys.body_vertices(int(b), x.data());
    const double v = mesh_volume(*sys.bodies()[b].topology, x.data());
    CHECK(std::abs(v / sys.bodies()[b].ref_volume - 1.0) < 0.01);
  }
  if (n_a > 0) {
    const Demixing m = demixing(sys);
    INFO("mean cell x " << m.mean_cell_x << ", leftmost adipocyte centre " << m.leftmost_centre_x
                        << "; closest cell behind an adipocyte: cell " << m.cell << " at x "
                        << m.cell_x << ", adipocyte centre x " << m.body_x << ", y-z distance "
                        << m.yz_distance);
    CHECK(m.mean_cell_x < m.leftmost_centre_x);
    CHECK(m.yz_distance >= 1.5);
  }
}

}  // namespace

TEST_CASE("the de-mixing criterion passes the de-mixed start and flags cells among adipocytes") {
  CHECK(demixing(dilute_start(28, 1500, 5)).yz_distance >= 1.5);
  const Demixing mixed = demixing(dilute_start(28, 1500, 5, nullptr, true));
  INFO("cell " << mixed.cell << " at x " << mixed.cell_x << ", adipocyte centre x "
               << mixed.body_x);
  CHECK(mixed.yz_distance < 1.5);
}

TEST_CASE("compression of cancer cells alone reaches phi = 0.72 in 3 % steps") {
  check_compression(0, 300, 1e-6, 1e-6);
}

// The paper's standard system (28 adipocytes, 1500 cells), as the compress stage does it.
TEST_CASE("compression of the paper's system reaches phi = 0.72, volumes kept, de-mixed",
          "[long]") {
  check_compression(28, 1500, 1e-3, 1e-6);
}

// The same with the compress stage's FIRE time step (lib/compress.lua: dt_max = 0.15 at
// eps_v = 1e3, below the adipocytes' volume-mode instability): the same checks hold, in under
// 100000 FIRE iterations (~46000; with the engine's dt_max 0.5, ~480000).
TEST_CASE(
    "compression of the paper's system with the stage's dt_max passes the same checks in "
    "10x fewer iterations",
    "[long]") {
  check_compression(28, 1500, 1e-3, 1e-6, 0.15, 100000);
}

// A compression stopped by its callback (a stop signal) after step k and continued
// with the report so far (as --resume does from compressing.ckpt, with fresh forces) ends
// bit for bit like one never stopped.
TEST_CASE("a compression stopped at a step boundary continues bit for bit") {
  ForceField ff = test::standard_forces(0.0, 1e3, 1.0);
  CompressionParams cp;
  cp.target_phi = 0.6;
  cp.fire.ftol = 1e-3;
  System straight = dilute_start(2, 40, 5);
  const CompressionReport whole = compress_to_phi(straight, ff, cp);
  REQUIRE(whole.steps > 10);
  System stopped = dilute_start(2, 40, 5);
  const std::size_t k = whole.steps / 2;
  const CompressionReport part =
      compress_to_phi(stopped, ff, cp, [&](const CompressionReport& r) { return r.steps < k; });
  CHECK(part.stopped);
  CHECK(part.steps == k);
  CHECK(part.phi < cp.target_phi);
  ForceField fresh = test::standard_forces(0.0, 1e3, 1.0);
  const CompressionReport rest = compress_to_phi(stopped, fresh, cp, {}, part);
  CHECK_FALSE(rest.stopped);
  CHECK(rest.steps == whole.steps);
  CHECK(rest.fire_steps == whole.fire_steps);
  CHECK(rest.max_force == whole.max_force);
  CHECK(rest.phi == whole.phi);
  std::size_t differing = 0;
  for (std::size_t i = 0; i < straight.n_sites(); ++i)
    differing += straight.sites().pos[i] != stopped.sites().pos[i];
  CHECK(differing == 0);
  // A stop asked for at the last step changes nothing: the target is reached.
  System last = dilute_start(2, 40, 5);
  const CompressionReport full = compress_to_phi(
      last, ff, cp, [&](const CompressionReport& r) { return r.steps < whole.steps; });
  CHECK_FALSE(full.stopped);
  CHECK(full.phi == whole.phi);
}

TEST_CASE("a compression stopped inside a FIRE continues bit for bit from a checkpoint") {
  ForceField ff = test::standard_forces(0.0, 1e3, 1.0);
  CompressionParams cp;
  cp.target_phi = 0.6;
  cp.fire.ftol = 1e-3;
  System straight = dilute_start(2, 40, 5);
  const CompressionReport whole = compress_to_phi(straight, ff, cp);
  REQUIRE(whole.fire_steps > 200);
  // Stop after a number of FIRE iterations that falls inside a step's minimisation.
  for (const std::uint64_t polls : {std::uint64_t(1), whole.fire_steps / 3, whole.fire_steps - 2}) {
    System stopped = dilute_start(2, 40, 5);
    std::uint64_t n = 0;
    const CompressionReport part =
        compress_to_phi(stopped, ff, cp, {}, {}, [&] { return ++n > polls; });
    REQUIRE(part.stopped);
    REQUIRE(part.fire_state);
    CHECK(part.fire_state->steps > 0);
    CHECK(part.fire_state->dt > 0.0);
    // Through a checkpoint of the System (velocities and all) into a fresh process's objects.
    CheckpointWriter w;
    write_system(w, stopped);
    System restored = read_system(CheckpointReader::parse(w.bytes(), "test"));
    ForceField fresh = test::standard_forces(0.0, 1e3, 1.0);
    const CompressionReport rest = compress_to_phi(restored, fresh, cp, {}, part);
    CHECK_FALSE(rest.stopped);
    CHECK_FALSE(rest.fire_state);
    CHECK(rest.steps == whole.steps);
    CHECK(rest.fire_steps == whole.fire_steps);
    CHECK(rest.max_force == whole.max_force);
    CHECK(rest.phi == whole.phi);
    std::size_t differing = 0;
    for (std::size_t i = 0; i < straight.n_sites(); ++i)
      differing += straight.sites().pos[i] != restored.sites().pos[i];
    CHECK(differing == 0);
  }
}

namespace {

// The unwrapped vertex positions of every adipocyte, per body.
std::vector<std::vector<Vec3>> body_positions(const System& sys) {
  std::vector<std::vector<Vec3>> out(sys.bodies().size());
  for (std::size_t b = 0; b < out.size(); ++b) {
    out[b].resize(std::size_t(sys.bodies()[b].n_vertices()));
    sys.body_vertices(int(b), out[b].data());
  }
  return out;
}

// The adipocyte packing fraction from the bodies' actual vertex positions and the box's
// corners: the union volume of each mesh and its vertex spheres (the paper's V_i, on a grid
// of spacing 0.05, as placement.hpp) over the box volume, not the V_i stored when the bodies
// were placed.
double measured_phi_a(const System& sys) {
  double v = 0.0;
  for (std::size_t b = 0; b < sys.bodies().size(); ++b) {
    const MeshBody& body = sys.bodies()[b];
    std::vector<Vec3> x(std::size_t(body.n_vertices()));
    sys.body_vertices(int(b), x.data());
    v += union_volume(*body.topology, x.data(), sys.sites().diameter[std::size_t(body.first_site)],
                      0.05);
  }
  const Vec3 edge = sys.box().hi() - sys.box().lo();
  return v / (edge[0] * edge[1] * edge[2]);
}

}  // namespace

TEST_CASE("rescale reaches the requested adipocyte packing fraction, bodies rigid") {
  ForceField ff = test::standard_forces(0.0, 1e3, 1.0);
  System sys = dilute_start(3, 50, 9);
  const Vec3 lo = sys.box().lo();
  const Vec3 edge_before = sys.box().hi() - lo;
  const double phi_a_before = measured_phi_a(sys);
  const auto before = body_positions(sys);
  std::vector<Vec3> cells_before;
  for (int i : sys.sites_of_kind(SiteKind::kCancer)) cells_before.push_back(sys.unwrapped(i));

  // The affine map alone (a FIRE of 0 iterations): the box shrank by the same factor on
  // every axis, s = cbrt(phi_a before / 0.05), phi_a from the geometry (not from the stored
  // V_i) is the target within the volume grid's error, every distance between two vertices
  // of a body is unchanged, and the bodies' vertex centroids and the cells moved as the map
  // of the box moves them: lo + s (r - lo).
  FireParams no_fire;
  no_fire.max_steps = 0;
  rescale_to_phi_a(sys, ff, 0.05, no_fire);
  const Vec3 edge_after = sys.box().hi() - sys.box().lo();
  const double s = std::cbrt(phi_a_before / 0.05);
  CHECK((sys.box().lo() - lo).norm() == 0.0);
  for (int a = 0; a < 3; ++a) CHECK(edge_after[a] == Approx(s * edge_before[a]).epsilon(2e-4));
  const double scale = edge_after[0] / edge_before[0];
  CHECK(measured_phi_a(sys) == Approx(0.05).epsilon(1e-3));
  CHECK(packing_fractions(sys).adipocyte == Approx(0.05).epsilon(1e-12));  // the stored V_i
  const auto after = body_positions(sys);
  double worst_distance = 0.0, worst_centre = 0.0;
  for (std::size_t b = 0; b < before.size(); ++b) {
    const int n = int(before[b].size());
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j)
        worst_distance = std::max(worst_distance, std::abs((after[b][i] - after[b][j]).norm() -
                                                           (before[b][i] - before[b][j]).norm()));
    const Vec3 c0 = vertex_centroid(n, before[b].data());
    const Vec3 c1 = vertex_centroid(n, after[b].data());
    worst_centre = std::max(worst_centre, (c1 - (lo + scale * (c0 - lo))).norm());
  }
  CHECK(worst_distance < 1e-9);
  CHECK(worst_centre < 1e-9);
  double worst_cell = 0.0;
  const std::vector<int> cells = sys.sites_of_kind(SiteKind::kCancer);
  for (std::size_t k = 0; k < cells.size(); ++k)
    worst_cell = std::max(worst_cell,
                          (sys.unwrapped(cells[k]) - (lo + scale * (cells_before[k] - lo))).norm());
  CHECK(worst_cell < 1e-9);

  // The whole rescale: the same box, and its FIRE converged (it relaxes the overlaps the map
  // made, deforming the bodies a little: phi_a from the geometry within 5 %).
  System relaxed = dilute_start(3, 50, 9);
  FireParams fp;
  fp.ftol = 1e-6;
  const FireResult fire = rescale_to_phi_a(relaxed, ff, 0.05, fp);
  CHECK(fire.converged);
  CHECK_FALSE(fire.stopped);
  CHECK(fire.max_force <= fp.ftol);
  CHECK((relaxed.box().hi() - sys.box().hi()).norm() == 0.0);
  CHECK(measured_phi_a(relaxed) == Approx(0.05).epsilon(0.05));
  CHECK_THROWS_WITH(rescale_to_phi_a(sys, ff, 1.5, fp), Contains("phi_a = 1.5 must be in (0, 1)"));
  // Nothing to scale: no adipocytes (phi_a = 0; the box would shrink to 0), an empty System
  // (phi = 0; the compression's box would be NaN). Both named, not a box error.
  System cells_only = dilute_start(0, 200, 9);
  System empty(Box(Vec3::Zero(), Vec3::Constant(10.0), {false, true, true}), 9);
  CHECK_THROWS_WITH(rescale_to_phi_a(cells_only, ff, 0.5, fp), Contains("(no adipocytes)"));
  CompressionParams cp;
  CHECK_THROWS_WITH(compress_to_phi(empty, ff, cp), Contains("there is nothing to compress"));
}
