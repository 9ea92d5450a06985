// FIRE minimiser: overlapping sphere packings, adipocytes with cells, and a pressure-controlled
// wall are taken to the force tolerance; the energy (enthalpy with a barostat) decreases.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "integrate/fire.hpp"
#include "mesh/geometry.hpp"
#include "test_support.hpp"

using namespace invasim;

namespace {

// Largest site force after a fresh evaluation (independent of FireResult).
double max_site_force(System& sys, ForceField& ff) {
  ff.compute(sys);
  double m = 0.0;
  for (const Vec3& f : sys.sites().force) m = std::max(m, f.norm());
  return m;
}

ForceField spheres_forces(bool walls, std::shared_ptr<WallForce>* wall_out = nullptr) {
  ForceField ff;
  ff.add(std::make_shared<ContactForce>(ContactParams{}));  // purely repulsive
  if (walls) {
    auto w = std::make_shared<WallForce>();
    ff.add(w);
    if (wall_out) *wall_out = w;
  }
  return ff;
}

// A relaxed state is a local minimum: random displacements of size h do not lower the energy
// beyond the first-order term allowed by the residual force.
void check_local_minimum(System& sys, ForceField& ff, double ftol, std::uint64_t seed) {
  const double e0 = ff.energy(sys);
  const std::vector<Vec3> pos = sys.sites().pos;
  const std::vector<Vec3i> img = sys.sites().image;
  const double h = 1e-4;
  const double allowed = ftol * h * std::sqrt(double(sys.n_sites())) * 10.0;
  for (int trial = 0; trial < 3; ++trial) {
    Sites& s = sys.sites();
    for (std::size_t i = 0; i < s.size(); ++i) {
      const auto g = RandomKey(seed, trial, std::uint32_t(i), RngStream::kUser).normal4();
      s.pos[i] += h * Vec3(g[0], g[1], g[2]);
      sys.box().wrap(s.pos[i], s.image[i]);
    }
    CHECK(ff.energy(sys) - e0 > -allowed);
    s.pos = pos;
    s.image = img;
  }
}

void report(const char* what, const FireResult& r, double e0, double e1) {
  std::printf("FIRE %-44s converged %d in %6llu steps, max |F| = %.3e, %.6g -> %.6g\n", what,
              int(r.converged), (unsigned long long)r.steps, r.max_force, e0, e1);
}

}  // namespace

TEST_CASE("FIRE relaxes an overlapping random packing of spheres (phi 0.7) to ftol 1e-8") {
  for (bool walls : {false, true}) {
    DYNAMIC_SECTION((walls ? "walls in x" : "fully periodic")) {
      System sys = test::random_spheres(300, 0.7, walls, 5);
      ForceField ff = spheres_forces(walls);
      const double e0 = ff.energy(sys);
      FireParams fp;
      fp.ftol = 1e-8;
      fp.max_steps = 20000;
      const FireResult r = Fire(fp).minimize(sys, ff);
      report(walls ? "spheres phi 0.7, walls" : "spheres phi 0.7, periodic", r, e0, r.energy);
      CHECK(r.converged);
      CHECK(r.max_force < fp.ftol);
      CHECK(max_site_force(sys, ff) < fp.ftol);
      // Above jamming the minimum keeps overlaps: positive energy, far below the start.
      CHECK(r.energy < 0.1 * e0);
      CHECK(r.energy > 0.0);
      CHECK(ff.energy(sys) == Approx(r.energy).epsilon(1e-12));
      for (const Vec3& v : sys.sites().vel) CHECK(v.squaredNorm() == 0.0);
      sys.validate();
      check_local_minimum(sys, ff, fp.ftol, 17);
    }
  }
}

TEST_CASE("FIRE stops at max_steps without claiming convergence") {
  System sys = test::random_spheres(300, 0.7, false, 5);
  ForceField ff = spheres_forces(false);
  FireParams fp;
  fp.ftol = 1e-8;
  fp.max_steps = 50;
  const FireResult r = Fire(fp).minimize(sys, ff);
  CHECK_FALSE(r.converged);
  CHECK(r.steps == 50);
  CHECK(r.max_force > fp.ftol);
  CHECK(max_site_force(sys, ff) == Approx(r.max_force).epsilon(1e-12));
}

TEST_CASE("FIRE relaxes adipocytes with cancer cells (contacts, cohesion, walls, shape)") {
  SECTION("8 jittered adipocytes among 200 cells (test::mixed_system), ftol 1e-8") {
    System sys = test::mixed_system(2, 200, 6.5, 0.2, 9);
    ForceField ff = test::standard_forces();
    const double e0 = ff.energy(sys);
    FireParams fp;
    fp.ftol = 1e-8;
    fp.max_steps = 20000;
    const FireResult r = Fire(fp).minimize(sys, ff);
    report("mixed_system(2, 200, 6.5), ftol 1e-8", r, e0, r.energy);
    CHECK(r.converged);
    CHECK(max_site_force(sys, ff) < fp.ftol);
    CHECK(r.energy < e0);
    // Force balance on every adipocyte: the sum of its vertex forces vanishes too.
    for (const MeshBody& b : sys.bodies()) {
      Vec3 f = Vec3::Zero();
      for (int v = 0; v < b.n_vertices(); ++v) f += sys.sites().force[b.first_site + v];
      CHECK(f.norm() < b.n_vertices() * fp.ftol);
      std::vector<Vec3> x(b.n_vertices());
      sys.body_vertices(int(&b - sys.bodies().data()), x.data());
      CHECK(mesh_volume(*b.topology, x.data()) == Approx(b.ref_volume).epsilon(0.02));
    }
    sys.validate();
  }
  SECTION("de-mixed slab: 2x2x2 adipocytes next to 100 cells (test::slab_system), ftol 1e-8") {
    System sys = test::slab_system(2, 2, 100, 6.0, 0.5, 9);
    ForceField ff = test::standard_forces();
    const double e0 = ff.energy(sys);
    FireParams fp;
    fp.ftol = 1e-8;
    fp.max_steps = 20000;
    const FireResult r = Fire(fp).minimize(sys, ff);
    report("slab_system(2, 2, 100, 6.0, 0.5), ftol 1e-8", r, e0, r.energy);
    CHECK(r.converged);
    CHECK(max_site_force(sys, ff) < fp.ftol);
    CHECK(r.energy < e0);
    sys.validate();
  }
}

TEST_CASE("FIRE relaxes a denser de-mixed slab (200 cells at phi_c 0.6) to ftol 1e-8", "[long]") {
  // ~9300 steps: cohesive cell clusters rearrange before the final basin is reached.
  System sys = test::slab_system(2, 2, 200, 6.0, 0.6, 9);
  ForceField ff = test::standard_forces();
  const double e0 = ff.energy(sys);
  FireParams fp;
  fp.ftol = 1e-8;
  fp.max_steps = 40000;
  const FireResult r = Fire(fp).minimize(sys, ff);
  report("slab_system(2, 2, 200, 6.0, 0.6), ftol 1e-8", r, e0, r.energy);
  CHECK(r.converged);
  CHECK(max_site_force(sys, ff) < fp.ftol);
  CHECK(r.energy < e0);
  sys.validate();
}

TEST_CASE("FIRE with a pressure-controlled left wall reaches mechanical equilibrium at P") {
  const double P = 1e-3;
  System sys = test::random_spheres(300, 0.7, true, 6);
  std::shared_ptr<WallForce> walls;
  ForceField ff = spheres_forces(true, &walls);
  PressureWall pw;
  pw.pressure = P;
  pw.walls = walls;  // default mass m = 1, as in the dynamics
  const double A = sys.box().wall_area();
  auto enthalpy = [&]() { return ff.energy(sys) + P * A * sys.box().length(0); };
  const double h0 = enthalpy(), lo0 = sys.box().lo()[0], hi0 = sys.box().hi()[0];
  FireParams fp;
  fp.ftol = 1e-8;
  fp.max_steps = 60000;
  const FireResult r = Fire(fp).minimize(sys, ff, &pw);
  CHECK(r.converged);
  CHECK(max_site_force(sys, ff) < fp.ftol);  // also refreshes the wall forces
  // Net force on the piston per unit area below ftol.
  const double net = walls->left_wall_force() + P * A;
  CHECK(std::abs(net) / A < fp.ftol);
  // The fixed right wall carries the same load: the site forces sum to minus the two wall
  // reactions, so |F_left + F_right| <= N ftol.
  CHECK(std::abs(walls->right_wall_force() - P * A) < (sys.n_sites() + A) * fp.ftol);
  CHECK(walls->right_wall_force() > 0.0);
  // phi 0.7 is over-compressed for P = 1e-3: the piston moved out, the right wall stayed, and
  // the enthalpy U + P V fell.
  CHECK(sys.box().lo()[0] < lo0 - 0.5);
  CHECK(sys.box().hi()[0] == hi0);
  const double h1 = enthalpy();
  report("spheres phi 0.7 + PressureWall P 1e-3 (U+PV)", r, h0, h1);
  CHECK(h1 < h0);
  sys.validate();
}

TEST_CASE("FIRE with a pressure wall moves a piston that starts out of balance with the sites") {
  // The sites start relaxed at fixed walls (every site force below ftol) but the piston is
  // pushed by P more than the packing pushes back: minimisation is not done until the piston
  // too is balanced, so the packing must be compressed, not returned as converged at once.
  System sys = test::random_spheres(200, 0.7, true, 8);
  std::shared_ptr<WallForce> walls;
  ForceField ff = spheres_forces(true, &walls);
  FireParams fp;
  fp.ftol = 1e-8;
  fp.max_steps = 60000;
  REQUIRE(Fire(fp).minimize(sys, ff).converged);
  REQUIRE(max_site_force(sys, ff) < fp.ftol);
  const double A = sys.box().wall_area();
  const double P = 2.0 * std::abs(walls->left_wall_force()) / A;  // twice the sites' push
  PressureWall pw;
  pw.pressure = P;
  pw.walls = walls;
  const double lo0 = sys.box().lo()[0];
  const FireResult r = Fire(fp).minimize(sys, ff, &pw);
  CHECK(r.converged);
  CHECK(r.steps > 0);
  CHECK(max_site_force(sys, ff) < fp.ftol);
  CHECK(std::abs(walls->left_wall_force() + P * A) / A < fp.ftol);
  CHECK(sys.box().lo()[0] > lo0);  // compressed: the piston moved in
}

TEST_CASE("FIRE stopped at an iteration boundary and resumed equals an uninterrupted run") {
  // With a pressure wall, so that the piston's velocity is part of the resumed state.
  auto setup = [](System& sys, ForceField& ff, PressureWall& pw) {
    sys = test::random_spheres(120, 0.7, true, 8);
    std::shared_ptr<WallForce> walls;
    ff = spheres_forces(true, &walls);
    pw.pressure = 1e-3;
    pw.walls = walls;
  };
  FireParams fp;
  fp.ftol = 1e-6;
  fp.max_steps = 60000;
  System a(test::cube(1.0, true), 1), b(test::cube(1.0, true), 1);
  ForceField fa, fb;
  PressureWall wa, wb;
  setup(a, fa, wa);
  setup(b, fb, wb);
  const FireResult whole = Fire(fp).minimize(a, fa, &wa);
  REQUIRE(whole.steps > 100);
  std::uint64_t polls = 0;
  FireControl stop;
  stop.stop = [&] { return ++polls > whole.steps / 2; };
  const FireResult part = Fire(fp).minimize(b, fb, &wb, &stop);
  REQUIRE(part.stopped);
  CHECK(part.state.steps == whole.steps / 2);
  CHECK(part.state.wall_velocity != 0.0);
  FireControl resume;
  resume.resume = part.state;
  ForceField fresh;  // new neighbour lists: forces do not depend on when a list was built
  std::shared_ptr<WallForce> walls;
  fresh = spheres_forces(true, &walls);
  wb.walls = walls;
  const FireResult rest = Fire(fp).minimize(b, fresh, &wb, &resume);
  CHECK_FALSE(rest.stopped);
  CHECK(rest.steps == whole.steps);
  CHECK(rest.max_force == whole.max_force);
  CHECK(rest.energy == whole.energy);
  CHECK(a.box().lo()[0] == b.box().lo()[0]);
  for (std::size_t i = 0; i < a.n_sites(); ++i) REQUIRE(a.sites().pos[i] == b.sites().pos[i]);
}

TEST_CASE("FIRE runs each iteration on the measured thread count, with identical results") {
  // Large enough for the contact kernel's parallel region (parallel_heavy).
  auto run = [](int threads, StepThreads* st) {
    System sys = test::random_spheres(1500, 0.7, true, 11);
    ForceField ff = spheres_forces(true);
    FireParams fp;
    fp.ftol = 1e-12;  // not reached: every run does max_steps iterations
    fp.max_steps = 300;
    FireControl control;
    control.threads = st;
    const ThreadCountScope scope(threads);
    const FireResult r = Fire(fp).minimize(sys, ff, nullptr, &control);
    return std::make_pair(r, sys.sites().pos);
  };
  StepThreads all;
  all.set_mode(StepThreads::Mode::kAll);
  const auto [r_all, pos_all] = run(2, &all);
  // Every iteration (and the final check that ends the loop) went through the measured choice.
  CHECK(all.team_steps() == r_all.steps + 1);
  CHECK(all.serial_steps() == 0);
  StepThreads measured;
  const auto [r_auto, pos_auto] = run(2, &measured);
  CHECK(measured.team_steps() + measured.serial_steps() == r_auto.steps + 1);
  const auto [r_one, pos_one] = run(1, nullptr);
  CHECK(r_all.steps == 300);
  CHECK(r_auto.energy == r_all.energy);
  CHECK(r_one.energy == r_all.energy);
  for (std::size_t i = 0; i < pos_all.size(); ++i) {
    REQUIRE(pos_auto[i] == pos_all[i]);
    REQUIRE(pos_one[i] == pos_all[i]);
  }
}
