// Force terms against their energies (finite differences), the virial, momentum balance,
// coincident sites, the shape energy's zero modes and the errors on bad input.
#include <catch2/catch.hpp>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <limits>

#include "core/errors.hpp"
#include "forces/shape_kernel.hpp"
#include "integrate/dynamics.hpp"
#include "mesh/geometry.hpp"
#include "test_support.hpp"

using namespace invasim;
using namespace invasim::test;
using Catch::Matchers::Contains;

namespace {

// Prints a measured number when INVASIM_TEST_VERBOSE is set.
void report(const char* what, double value) {
  if (std::getenv("INVASIM_TEST_VERBOSE")) std::printf("  %-58s %.3e\n", what, value);
}

// The pair forms of docs/model.md ("Forces"), written independently of the engine.
double model_linear_energy(double r, double s, double eps) {
  return r >= s ? 0.0 : 0.5 * eps * (1.0 - r / s) * (1.0 - r / s);
}
double model_linear_force(double r, double s, double eps) {
  return r >= s ? 0.0 : eps / s * (1.0 - r / s);
}
double model_cohesive_force(double r, double s, double eps, double alpha, double beta) {
  const double ra = (1 + alpha) * s, rb = (1 + beta) * s;
  if (r <= rb) return eps / s * (1.0 - r / s);
  if (r <= ra) return eps / s * (rb - s) / (ra - rb) * (r - ra) / s;
  return 0.0;
}
// U(r) = integral of F from r to r_a; F is linear on [0, s], [s, r_b], [r_b, r_a].
double model_cohesive_energy(double r, double s, double eps, double alpha, double beta) {
  const double ra = (1 + alpha) * s, rb = (1 + beta) * s;
  if (r >= ra) return 0.0;
  auto F = [&](double x) { return model_cohesive_force(x, s, eps, alpha, beta); };
  auto trap = [&](double a, double b) { return a < b ? 0.5 * (b - a) * (F(a) + F(b)) : 0.0; };
  return trap(r, std::min(s, ra)) + trap(std::max(r, s), rb) + trap(std::max(r, rb), ra);
}

// Brute-force contact energy over all pairs (minimum image); counts pairs per branch:
// [0] cc r<s, [1] cc s<r<r_b, [2] cc r_b<r<r_a, [3] cancer-vertex, [4] vertex-vertex.
double brute_contact_energy(const System& sys, const ContactParams& p, std::array<int, 5>* n) {
  const Sites& s = sys.sites();
  double e = 0.0;
  if (n) n->fill(0);
  for (std::size_t i = 0; i < s.size(); ++i)
    for (std::size_t j = i + 1; j < s.size(); ++j) {
      if (s.body[i] >= 0 && s.body[i] == s.body[j]) continue;
      const double r = sys.box().minimum_image(s.pos[i] - s.pos[j]).norm();
      const double sig = 0.5 * (s.diameter[i] + s.diameter[j]);
      const int kinds = int(s.kind[i]) + int(s.kind[j]);
      if (kinds == 1 && p.beta_cv > 0.0) {  // cancer-vertex adhesion (its own branch count)
        e += model_cohesive_energy(r, sig, p.eps_cv, p.alpha_cv, p.beta_cv);
        if (n && r < sig) ++(*n)[3];
      } else if (kinds == 0 && p.beta > 0.0) {
        e += model_cohesive_energy(r, sig, p.eps_cc, p.alpha, p.beta);
        if (n) {
          if (r < sig)
            ++(*n)[0];
          else if (r < (1 + p.beta) * sig)
            ++(*n)[1];
          else if (r < (1 + p.alpha) * sig)
            ++(*n)[2];
        }
      } else {
        const double eps = kinds == 0 ? p.eps_cc : kinds == 1 ? p.eps_cv : p.eps_vv;
        e += model_linear_energy(r, sig, eps);
        if (n && r < sig && kinds > 0) ++(*n)[2 + kinds];
      }
    }
  return e;
}

// Brute-force contact forces from the pair forms of docs/model.md (all pairs, minimum image).
std::vector<Vec3> brute_contact_forces(const System& sys, const ContactParams& p) {
  const Sites& s = sys.sites();
  std::vector<Vec3> f(s.size(), Vec3::Zero());
  for (std::size_t i = 0; i < s.size(); ++i)
    for (std::size_t j = i + 1; j < s.size(); ++j) {
      if (s.body[i] >= 0 && s.body[i] == s.body[j]) continue;
      const Vec3 d = sys.box().minimum_image(s.pos[i] - s.pos[j]);
      const double r = d.norm(), sig = 0.5 * (s.diameter[i] + s.diameter[j]);
      const int kinds = int(s.kind[i]) + int(s.kind[j]);
      const double eps = kinds == 0 ? p.eps_cc : kinds == 1 ? p.eps_cv : p.eps_vv;
      const double mag =
          kinds == 0 && p.beta > 0.0      ? model_cohesive_force(r, sig, eps, p.alpha, p.beta)
          : kinds == 1 && p.beta_cv > 0.0 ? model_cohesive_force(r, sig, eps, p.alpha_cv, p.beta_cv)
                                          : model_linear_force(r, sig, eps);
      f[i] += mag * d / r;
      f[j] -= mag * d / r;
    }
  return f;
}

// a - b to the nearest image of a (walls in x, periodic y and z), by search over images.
Vec3 nearest_image(const Box& box, const Vec3& a, const Vec3& b) {
  Vec3 best = a - b;
  for (int k = -2; k <= 2; ++k)
    for (int l = -2; l <= 2; ++l) {
      const Vec3 d = a - b + Vec3(0.0, k * box.length(1), l * box.length(2));
      if (d.norm() < best.norm()) best = d;
    }
  return best;
}

// Minimum-image distance by search over the neighbouring images in y and z.
double image_distance(const Box& box, const Vec3& a, const Vec3& b) {
  return nearest_image(box, a, b).norm();
}

struct FdCheck {
  double rel_err = 0.0;    // max over sites of |F_fd - F| / max |F|
  double max_force = 0.0;  // max |F|
};

// Central differences of ff's energy against ff's forces, site by site.
FdCheck fd_check(System& sys, ForceField& ff, double h = 1e-6) {
  const ForceFlags e{true, false};
  ff.compute(sys, e);
  const std::vector<Vec3> f = sys.sites().force;
  FdCheck out;
  double err = 0.0;
  for (std::size_t i = 0; i < sys.n_sites(); ++i) {
    out.max_force = std::max(out.max_force, f[i].norm());
    Vec3 fd;
    for (int a = 0; a < 3; ++a) {
      Vec3& p = sys.sites().pos[i];
      const double x0 = p[a], xp = x0 + h, xm = x0 - h;
      p[a] = xp;
      const double up = ff.compute(sys, e).energy;
      p[a] = xm;
      const double dn = ff.compute(sys, e).energy;
      p[a] = x0;
      fd[a] = -(up - dn) / (xp - xm);
    }
    err = std::max(err, (fd - f[i]).norm());
  }
  out.rel_err = err / out.max_force;
  ff.compute(sys, e);
  return out;
}

ForceField field_of(std::shared_ptr<Force> f) {
  ForceField ff;
  ff.add(std::move(f));
  return ff;
}

// W_aa = -dU/d(ln L_a) by central differences under System::scale (everything affine);
// make() returns a fresh force field each time so no neighbour list is shared.
Vec3 fd_virial(const System& sys, const std::function<ForceField()>& make, double delta = 1e-6) {
  Vec3 w;
  for (int a = 0; a < 3; ++a) {
    double e[2];
    for (int k = 0; k < 2; ++k) {
      System c = sys;
      Vec3 s = Vec3::Ones();
      s[a] = std::exp(k == 0 ? delta : -delta);
      c.scale(s, false);
      ForceField ff = make();
      e[k] = ff.energy(c);
    }
    w[a] = -(e[0] - e[1]) / (2.0 * delta);
  }
  return w;
}

// Compares the engine's virial with fd_virial; returns max |diff| / max |W|.
double virial_error(System& sys, const std::function<ForceField()>& make, const char* what) {
  ForceField ff = make();
  const Vec3 w = ff.compute(sys, {true, true}).virial;
  const Vec3 fd = fd_virial(sys, make);
  const double scale = w.cwiseAbs().maxCoeff();
  const double err = (w - fd).cwiseAbs().maxCoeff() / scale;
  INFO(what << ": W = " << w.transpose() << ", -dU/dlnL = " << fd.transpose());
  CHECK(scale > 1e-2);
  CHECK(err < 1e-6);
  report(what, err);
  return err;
}

// Random displacement of every vertex of body b by up to +-amp per component.
void jitter_body(System& sys, int b, double amp, std::uint64_t seed) {
  const MeshBody& body = sys.bodies()[b];
  for (int v = 0; v < body.n_vertices(); ++v) {
    const std::uint32_t id = 7000 + 64 * b + v;
    sys.sites().pos[body.first_site + v] +=
        2.0 * amp *
        Vec3(uniform(seed, id, 0) - 0.5, uniform(seed, id, 1) - 0.5, uniform(seed, id, 2) - 0.5);
  }
}

Vec3 force_sum(const System& sys) {
  Vec3 t = Vec3::Zero();
  for (const Vec3& f : sys.sites().force) t += f;
  return t;
}
double max_force(const System& sys) {
  double m = 0.0;
  for (const Vec3& f : sys.sites().force) m = std::max(m, f.norm());
  return m;
}

// Adipocytes (radius 2, vertex diameter 2) whose centres are on a 2 x 3 x 3 grid of spacing 6,
// randomly displaced, in a box walled in x and periodic (length 18) in y and z.
System tether_system(std::uint64_t seed) {
  System sys(Box(Vec3::Zero(), Vec3(12.0, 18.0, 18.0), {false, true, true}), seed);
  const MeshShape shape = icosphere(1);
  int b = 0;
  for (int gx = 0; gx < 2; ++gx)
    for (int gy = 0; gy < 3; ++gy)
      for (int gz = 0; gz < 3; ++gz, ++b) {
        const Vec3 jit(uniform(seed, b, 0) - 0.5, uniform(seed, b, 1) - 0.5,
                       uniform(seed, b, 2) - 0.5);
        const Vec3 c = Vec3(3.0 + 6.0 * gx, 1.0 + 6.0 * gy, 6.0 * gz - 1.0) + 1.5 * jit;
        sys.add_mesh_scaled(shape, c, 2.0, 2.0, 1.1);
        jitter_body(sys, b, 0.2, seed);
      }
  sys.wrap_all();
  return sys;
}

// Moves every body rigidly by a random displacement of up to +-amp per component.
void displace_bodies(System& sys, double amp, std::uint64_t seed) {
  for (std::size_t b = 0; b < sys.bodies().size(); ++b) {
    const Vec3 d = 2.0 * amp *
                   Vec3(uniform(seed, 500 + b, 0) - 0.5, uniform(seed, 500 + b, 1) - 0.5,
                        uniform(seed, 500 + b, 2) - 0.5);
    const MeshBody& body = sys.bodies()[b];
    for (int v = 0; v < body.n_vertices(); ++v) sys.sites().pos[body.first_site + v] += d;
  }
  sys.wrap_all();
}

// Tethers: mean degree 6 plus two manual ones (stretched and compressed), bodies displaced.
std::shared_ptr<TetherForce> make_tethers(System& sys, double k) {
  auto tf = std::make_shared<TetherForce>(k);
  tf->connect_by_mean_degree(sys, 6.0);
  const auto c = TetherForce::body_centres(sys);
  tf->add(sys, 0, 17, 0.5 * sys.box().minimum_image(c[0] - c[17]).norm());
  tf->add(sys, 3, 8, 1.5 * sys.box().minimum_image(c[3] - c[8]).norm());
  displace_bodies(sys, 0.8, 99);
  return tf;
}

// Two adipocytes and perturbed meshes with reference state away from the current one;
// body 0 straddles the periodic y and z edges.
System shape_system(std::uint64_t seed) {
  System sys(Box(Vec3::Zero(), Vec3(12.0, 12.0, 12.0), {false, true, true}), seed);
  const MeshShape shape = icosphere(1);
  sys.add_mesh_scaled(shape, Vec3(4.0, 0.5, 11.7), 2.0, 2.0, 1.1);
  sys.add_mesh_scaled(shape, Vec3(8.0, 6.0, 6.0), 1.7, 2.0, 1.05);
  jitter_body(sys, 0, 0.3, seed);
  jitter_body(sys, 1, 0.25, seed);
  sys.bodies()[0].ref_volume *= 1.08;
  sys.bodies()[1].ref_volume *= 0.93;
  sys.wrap_all();
  return sys;
}

// Spheres within 1.3 diameters of either wall of a box walled at x = -3 and x = 5.
System near_walls(int n, std::uint64_t seed) {
  System sys(Box(Vec3(-3.0, 0.0, 0.0), Vec3(5.0, 6.0, 6.0), {false, true, true}), seed);
  for (int i = 0; i < n; ++i) {
    const double d = i % 2 ? 1.1 : 0.9;
    const double u = uniform(seed, i, 0) * 1.3 * d;
    const double x = i % 4 < 2 ? -3.0 + u : 5.0 - u;
    sys.add_sphere(Vec3(x, 6.0 * uniform(seed, i, 1), 6.0 * uniform(seed, i, 2)), d);
  }
  return sys;
}

ContactParams cohesive_params() {
  ContactParams p;
  p.alpha = 0.2;
  p.beta = 1e-2;
  return p;
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Pair forms

TEST_CASE(
    "linear_spring matches the model: F = (eps/s)(1 - r/s), U = eps/2 (1 - r/s)^2, 0 beyond s") {
  const double s = 1.1, eps = 0.7;
  CHECK(linear_spring(0.0, s, eps).force == Approx(eps / s).epsilon(1e-15));
  CHECK(linear_spring(0.0, s, eps).energy == Approx(eps / 2).epsilon(1e-15));
  CHECK(linear_spring(0.5 * s, s, eps).force == Approx(eps / (2 * s)).epsilon(1e-15));
  CHECK(linear_spring(0.5 * s, s, eps).energy == Approx(eps / 8).epsilon(1e-15));
  CHECK(linear_spring(s, s, eps).force == 0.0);
  CHECK(linear_spring(s, s, eps).energy == 0.0);
  CHECK(linear_spring(1.3 * s, s, eps).force == 0.0);
  CHECK(linear_spring(1.3 * s, s, eps).energy == 0.0);
  for (double r = 0.0; r < 1.5 * s; r += 0.0137) {
    CHECK(linear_spring(r, s, eps).force == Approx(model_linear_force(r, s, eps)).margin(1e-14));
    CHECK(linear_spring(r, s, eps).energy == Approx(model_linear_energy(r, s, eps)).margin(1e-14));
  }
}

TEST_CASE(
    "cohesive_spring matches the model: continuous, -eps beta/s at r_b, zero at r_a and beyond") {
  const double eps = 1.0, alpha = 0.2;
  for (double beta : {1e-4, 1e-3, 1e-2}) {
    for (double s : {0.9, 1.0, 1.1}) {
      CAPTURE(beta, s);
      const double ra = (1 + alpha) * s, rb = (1 + beta) * s, tiny = 1e-12;
      // Values at specific separations.
      CHECK(cohesive_spring(0.0, s, eps, alpha, beta).force == Approx(eps / s).epsilon(1e-14));
      CHECK(cohesive_spring(0.5 * s, s, eps, alpha, beta).force ==
            Approx(eps / (2 * s)).epsilon(1e-14));
      CHECK(cohesive_spring(s, s, eps, alpha, beta).force == Approx(0.0).margin(1e-15));
      CHECK(cohesive_spring(rb, s, eps, alpha, beta).force ==
            Approx(-eps * beta / s).epsilon(1e-12));
      CHECK(cohesive_spring(0.5 * (rb + ra), s, eps, alpha, beta).force ==
            Approx(-eps * beta / (2 * s)).epsilon(1e-12));
      CHECK(cohesive_spring(ra, s, eps, alpha, beta).force == Approx(0.0).margin(1e-15));
      CHECK(cohesive_spring(ra, s, eps, alpha, beta).energy == Approx(0.0).margin(1e-15));
      CHECK(cohesive_spring(ra + tiny, s, eps, alpha, beta).force == 0.0);
      CHECK(cohesive_spring(ra + tiny, s, eps, alpha, beta).energy == 0.0);
      CHECK(cohesive_spring(2.0 * s, s, eps, alpha, beta).energy == 0.0);
      // Energy minimum -eps alpha beta / 2 at r = s; -eps beta (alpha - beta)/2 at r_b.
      CHECK(cohesive_spring(s, s, eps, alpha, beta).energy ==
            Approx(-0.5 * eps * alpha * beta).epsilon(1e-12));
      CHECK(cohesive_spring(rb, s, eps, alpha, beta).energy ==
            Approx(-0.5 * eps * beta * (alpha - beta)).epsilon(1e-12));
      CHECK(cohesive_spring(0.0, s, eps, alpha, beta).energy ==
            Approx(0.5 * eps * (1 - alpha * beta)).epsilon(1e-14));
      // The most attractive force is at r_b.
      double fmin = 0.0;
      for (double r = 0.0; r < 1.3 * s; r += 1e-4 * s)
        fmin = std::min(fmin, cohesive_spring(r, s, eps, alpha, beta).force);
      CHECK(fmin >= -eps * beta / s * (1 + 1e-12));
      // Force and energy continuous at s, r_b and r_a.
      for (double r0 : {s, rb, ra}) {
        const PairEval lo = cohesive_spring(r0 - tiny, s, eps, alpha, beta);
        const PairEval hi = cohesive_spring(r0 + tiny, s, eps, alpha, beta);
        CHECK(lo.force == Approx(hi.force).margin(1e-10));
        CHECK(lo.energy == Approx(hi.energy).margin(1e-10));
      }
      // Force and energy equal the model's piecewise force and its integral everywhere.
      for (double r = 0.0; r < 1.4 * s; r += 0.00731) {
        const PairEval pe = cohesive_spring(r, s, eps, alpha, beta);
        CHECK(pe.force == Approx(model_cohesive_force(r, s, eps, alpha, beta)).margin(1e-13));
        CHECK(pe.energy == Approx(model_cohesive_energy(r, s, eps, alpha, beta)).margin(1e-13));
      }
    }
  }
  // beta = 0 is the purely repulsive spring.
  CHECK(cohesive_spring(1.05, 1.0, 1.0, 0.2, 0.0).force == 0.0);
  CHECK(cohesive_spring(0.5, 1.0, 1.0, 0.2, 0.0).energy == Approx(0.125));
}

// ---------------------------------------------------------------------------------------
// Contact forces

TEST_CASE(
    "contact energy and forces equal the all-pairs model sums, same-adipocyte vertices "
    "excluded") {
  for (double skin : {0.0, 0.3}) {
    CAPTURE(skin);
    ContactParams p = cohesive_params();
    p.eps_cc = 1.0;
    p.eps_cv = 0.7;
    p.eps_vv = 1.3;
    p.skin = skin;
    System sys = mixed_system(2, 80, 4.6, 0.4, 11);
    std::array<int, 5> n;
    const double ref = brute_contact_energy(sys, p, &n);
    ForceField ff = field_of(std::make_shared<ContactForce>(p));
    const double e = ff.compute(sys, {true, false}).energy;
    INFO("pairs: cc overlap " << n[0] << ", cc s..r_b " << n[1] << ", cc r_b..r_a " << n[2]
                              << ", cancer-vertex " << n[3] << ", vertex-vertex " << n[4]);
    CHECK(n[2] > 5);
    CHECK(n[3] > 20);
    CHECK(n[4] > 20);
    CHECK(e == Approx(ref).epsilon(1e-12));
    const std::vector<Vec3> fb = brute_contact_forces(sys, p);
    double err = 0.0;
    for (std::size_t i = 0; i < fb.size(); ++i)
      err = std::max(err, (fb[i] - sys.sites().force[i]).norm());
    CHECK(err < 1e-12 * max_force(sys));
  }

  // One adipocyte alone: its vertices overlap (vertex diameter 2 > edge length) yet feel nothing.
  System one = mixed_system(1, 0, 8.0, 0.3, 12);
  double min_edge = 1e9;
  for (const auto& [a, b] : one.bodies()[0].topology->edges())
    min_edge = std::min(min_edge, (one.unwrapped(a) - one.unwrapped(b)).norm());
  REQUIRE(min_edge < 2.0);
  ForceField f1 = field_of(std::make_shared<ContactForce>(cohesive_params()));
  CHECK(f1.compute(one, {true, true}).energy == 0.0);
  CHECK(max_force(one) == 0.0);
}

TEST_CASE(
    "contact kernel: class table for few diameters (looked up by permutes up to 16 class pairs, "
    "by loads beyond), direct fallback for many, all equal the all-pairs sums, and forces do not "
    "depend on the skin, bit for bit") {
  // 0: the bidisperse cells (3 classes with the vertices); 5 and 20 distinct cancer-cell
  // diameters: 6 classes (36 class pairs, more than a permute holds), and more classes than
  // the table takes.
  for (int diameters : {0, 5, 20}) {
    CAPTURE(diameters);
    const bool many = diameters > PairTable::kMaxClasses;
    System sys = mixed_system(2, 80, 4.6, 0.4, 11);
    if (diameters > 0)
      for (std::size_t i = 0; i < sys.n_sites(); ++i)
        if (sys.sites().kind[i] == SiteKind::kCancer)
          sys.sites().diameter[i] = 0.9 + 0.01 * double(i % std::size_t(diameters));
    ContactParams p = cohesive_params();
    p.eps_cv = 0.7;
    p.eps_vv = 1.3;
    PairTable table;
    CHECK(table.build(sys.sites(), p) == !many);
    if (diameters == 0) CHECK(table.n_classes() == 3);  // cancer 0.9 and 1.1, vertices
    if (diameters == 5) CHECK(table.n_classes() * table.n_classes() > PairTable::kLookupEntries);
    std::vector<Vec3> first;
    for (double skin : {0.0, 0.3, 0.77}) {
      CAPTURE(skin);
      p.skin = skin;
      ForceField ff = field_of(std::make_shared<ContactForce>(p));
      const ForceResult res = ff.compute(sys, {true, true});
      CHECK(res.energy == Approx(brute_contact_energy(sys, p, nullptr)).epsilon(1e-12));
      const std::vector<Vec3> fb = brute_contact_forces(sys, p);
      double err = 0.0;
      for (std::size_t i = 0; i < fb.size(); ++i)
        err = std::max(err, (fb[i] - sys.sites().force[i]).norm());
      CHECK(err < 1e-12 * max_force(sys));
      if (first.empty()) first = sys.sites().force;
      CHECK(sys.sites().force == first);
    }
  }
}

TEST_CASE(
    "PairTable: the branches' constants interleaved per class pair (2t repulsive, 2t+1 "
    "attractive) equal pair_coefficients") {
  // The kernel looks each entry's constants up at t = ci * n_classes + cj (look_up_pairs);
  // this layout is what it relies on.
  System sys = mixed_system(2, 40, 4.6, 0.4, 12);
  ContactParams p = cohesive_params();
  p.eps_cv = 0.7;
  p.eps_vv = 1.3;
  p.alpha_cv = 0.3;  // cancer-vertex pairs on their own attractive branch
  p.beta_cv = 0.05;
  PairTable table;
  REQUIRE(table.build(sys.sites(), p));
  const int nc = table.n_classes();
  REQUIRE(nc == 3);
  const Sites& s = sys.sites();
  int checked = 0;
  for (std::size_t i = 0; i < s.size(); ++i)
    for (std::size_t j = 0; j < s.size(); j += 7) {
      const std::size_t t = std::size_t(table.site_class()[i] * nc + table.site_class()[j]);
      const PairCoefficients c =
          pair_coefficients(p, s.kind[i], s.kind[j], s.diameter[i], s.diameter[j]);
      CHECK(table.rc2[t] == c.rc2);
      CHECK(table.rb2[t] == c.rb2);
      CHECK(table.tiny2[t] == c.tiny2);
      CHECK(table.c_rep[t] == c.c_rep);
      CHECK(table.c_att[t] == c.c_att);
      CHECK(table.d_rep[t] == c.d_rep);
      CHECK(table.d_att[t] == c.d_att);
      CHECK(table.r0_rep[t] == c.r0_rep);
      CHECK(table.r0_att[t] == c.r0_att);
      CHECK(table.e0[t] == c.e0);
      ++checked;
    }
  CHECK(checked > 1000);
}

TEST_CASE("contact forces are minus the gradient of the contact energy (finite differences)") {
  SECTION("cancer-cancer with cohesion, all three branches, periodic box") {
    const ContactParams p = cohesive_params();
    System sys = random_spheres(250, 0.5, false, 21);
    std::array<int, 5> n;
    brute_contact_energy(sys, p, &n);
    INFO("cc pairs: r<s " << n[0] << ", s<r<r_b " << n[1] << ", r_b<r<r_a " << n[2]);
    report("cc pairs r < s", n[0]);
    report("cc pairs s < r < r_b", n[1]);
    report("cc pairs r_b < r < r_a", n[2]);
    REQUIRE(n[0] > 50);
    REQUIRE(n[1] >= 5);
    REQUIRE(n[2] > 50);
    ForceField ff = field_of(std::make_shared<ContactForce>(p));
    const FdCheck r = fd_check(sys, ff);
    CHECK(r.max_force > 0.1);
    CHECK(r.rel_err < 1e-6);
    report("FD contact cancer-cancer cohesive (periodic)", r.rel_err);
  }
  SECTION("cancer-cancer with cohesion, walled box") {
    const ContactParams p = cohesive_params();
    System sys = random_spheres(150, 0.5, true, 22);
    ForceField ff = field_of(std::make_shared<ContactForce>(p));
    const FdCheck r = fd_check(sys, ff);
    CHECK(r.max_force > 0.1);
    CHECK(r.rel_err < 1e-6);
    report("FD contact cancer-cancer cohesive (walled)", r.rel_err);
  }
  SECTION("cancer-cancer, cancer-vertex and vertex-vertex, distinct eps per kind") {
    ContactParams p = cohesive_params();
    p.eps_cc = 1.0;
    p.eps_cv = 0.7;
    p.eps_vv = 1.3;
    System sys = mixed_system(2, 50, 4.6, 0.4, 23);
    std::array<int, 5> n;
    brute_contact_energy(sys, p, &n);
    REQUIRE(n[3] > 20);
    REQUIRE(n[4] > 20);
    ForceField ff = field_of(std::make_shared<ContactForce>(p));
    const FdCheck r = fd_check(sys, ff);
    CHECK(r.max_force > 0.1);
    CHECK(r.rel_err < 1e-6);
    report("FD contact mixed (cc, cv, vv)", r.rel_err);
  }
  SECTION("cancer-vertex adhesion (alpha_cv, beta_cv) beside the cells' cohesion") {
    ContactParams p = cohesive_params();
    p.eps_cv = 0.7;
    p.alpha_cv = 0.3;
    p.beta_cv = 0.05;
    System sys = mixed_system(2, 50, 4.6, 0.4, 25);
    // cancer-vertex pairs on each branch: overlapping, s < r < r_b, r_b < r < r_a
    std::array<int, 3> cv{0, 0, 0};
    const Sites& s = sys.sites();
    for (std::size_t i = 0; i < s.size(); ++i)
      for (std::size_t j = i + 1; j < s.size(); ++j) {
        if (s.kind[i] == s.kind[j]) continue;
        const double r = sys.box().minimum_image(s.pos[i] - s.pos[j]).norm();
        const double sig = 0.5 * (s.diameter[i] + s.diameter[j]);
        if (r < sig)
          ++cv[0];
        else if (r < (1 + p.beta_cv) * sig)
          ++cv[1];
        else if (r < (1 + p.alpha_cv) * sig)
          ++cv[2];
      }
    INFO("cancer-vertex pairs: r<s " << cv[0] << ", s<r<r_b " << cv[1] << ", r_b<r<r_a " << cv[2]);
    REQUIRE(cv[0] > 20);
    REQUIRE(cv[1] >= 3);
    REQUIRE(cv[2] > 20);
    ForceField ff = field_of(std::make_shared<ContactForce>(p));
    const FdCheck r = fd_check(sys, ff);
    CHECK(r.max_force > 0.1);
    CHECK(r.rel_err < 1e-6);
    // The energy is the model's, adhesion included (and differs from the repulsive one).
    const double e = ff.compute(sys, {true, false}).energy;
    CHECK(e == Approx(brute_contact_energy(sys, p, nullptr)).epsilon(1e-12));
    ContactParams no_adhesion = p;
    no_adhesion.beta_cv = 0.0;
    CHECK(e < brute_contact_energy(sys, no_adhesion, nullptr) - 1e-3);
    report("FD contact with cancer-vertex adhesion", r.rel_err);
    // The same through the per-pair constants (more diameter classes than the table holds).
    for (std::size_t i = 0; i < sys.n_sites(); ++i)
      if (sys.sites().kind[i] == SiteKind::kCancer)
        sys.sites().diameter[i] = 0.9 + 0.01 * double(i % 20);
    PairTable table;
    REQUIRE_FALSE(table.build(sys.sites(), p));
    ForceField direct = field_of(std::make_shared<ContactForce>(p));
    CHECK(direct.compute(sys, {true, false}).energy ==
          Approx(brute_contact_energy(sys, p, nullptr)).epsilon(1e-12));
    CHECK(fd_check(sys, direct).rel_err < 1e-6);
  }
  SECTION("purely repulsive (beta = 0)") {
    ContactParams p;
    System sys = mixed_system(2, 50, 4.6, 0.4, 24);
    ForceField ff = field_of(std::make_shared<ContactForce>(p));
    const FdCheck r = fd_check(sys, ff);
    CHECK(r.max_force > 0.1);
    CHECK(r.rel_err < 1e-6);
    report("FD contact mixed, beta = 0", r.rel_err);
  }
}

TEST_CASE("coincident and nearly coincident sites: finite, equal and opposite, magnitude eps/s") {
  const ContactParams p = cohesive_params();
  for (double sep : {0.0, 1e-15, 1e-13, 1e-10}) {
    for (int kinds = 0; kinds < 3; ++kinds) {  // cancer-cancer, cancer-vertex, vertex-vertex
      CAPTURE(sep, kinds);
      System sys(cube(12.0, true), 5);
      const MeshShape shape = icosphere(1);
      // Two adipocytes far apart; the probe sites are a cancer cell or one vertex of each.
      sys.add_mesh_scaled(shape, Vec3(3.0, 3.0, 3.0), 1.5, 1.2, 1.1);
      sys.add_mesh_scaled(shape, Vec3(9.0, 9.0, 9.0), 1.5, 1.2, 1.1);
      const Vec3 at(6.0, 6.0, 6.0);
      int i, j;
      if (kinds == 0) {
        i = sys.add_sphere(at, 0.9);
        j = sys.add_sphere(at + Vec3(0.0, sep, 0.0), 1.1);
      } else if (kinds == 1) {
        i = sys.add_sphere(at, 0.9);
        j = 0;
        sys.sites().pos[j] = at + Vec3(0.0, 0.0, sep);
      } else {
        i = 0;
        j = 42;
        sys.sites().pos[i] = at;
        sys.sites().pos[j] = at + Vec3(sep, 0.0, 0.0);
      }
      const double s = 0.5 * (sys.sites().diameter[i] + sys.sites().diameter[j]);
      const double eps = kinds == 0 ? p.eps_cc : kinds == 1 ? p.eps_cv : p.eps_vv;
      ForceField ff = field_of(std::make_shared<ContactForce>(p));
      const ForceResult res = ff.compute(sys, {true, true});
      const Vec3 fi = sys.sites().force[i], fj = sys.sites().force[j];
      CHECK(fi.allFinite());
      CHECK(fj.allFinite());
      CHECK(std::isfinite(res.energy));
      CHECK(res.virial.allFinite());
      CHECK(fi.norm() == Approx(eps / s * (1 - sep / s)).epsilon(1e-14));
      CHECK((fi + fj).norm() == 0.0);
      const double x = 1 - sep / s;
      const double e_pair = kinds == 0 ? 0.5 * eps * (x * x - p.alpha * p.beta) : 0.5 * eps * x * x;
      CHECK(res.energy == Approx(e_pair).epsilon(1e-14));
    }
  }
}

// ---------------------------------------------------------------------------------------
// Walls, shape, tethers

TEST_CASE(
    "wall energy, forces and reactions equal the model's: (eps/s)(1 - d/s) into the box, s = own "
    "diameter") {
  System sys = near_walls(120, 33);
  sys.sites().pos[0][0] = -3.05;
  sys.sites().pos[3][0] = 5.04;
  const double eps = 1.3, xl = -3.0, xr = 5.0;
  auto wf = std::make_shared<WallForce>(eps);
  ForceField ff = field_of(wf);
  const double e = ff.compute(sys, {true, false}).energy;
  double e_ref = 0.0, left = 0.0, right = 0.0, err = 0.0;
  int n_left = 0, n_right = 0;
  for (std::size_t i = 0; i < sys.n_sites(); ++i) {
    const double x = sys.sites().pos[i][0], s = sys.sites().diameter[i];
    double f = 0.0;
    if (x - xl <= s) {
      e_ref += 0.5 * eps * (1 - (x - xl) / s) * (1 - (x - xl) / s);
      f += eps / s * (1 - (x - xl) / s);
      left -= eps / s * (1 - (x - xl) / s);
      ++n_left;
    }
    if (xr - x <= s) {
      e_ref += 0.5 * eps * (1 - (xr - x) / s) * (1 - (xr - x) / s);
      f -= eps / s * (1 - (xr - x) / s);
      right += eps / s * (1 - (xr - x) / s);
      ++n_right;
    }
    err = std::max(err, (sys.sites().force[i] - Vec3(f, 0.0, 0.0)).norm());
  }
  CHECK(n_left > 20);
  CHECK(n_right > 20);
  CHECK(n_left + n_right < 120);  // some sites are out of range
  CHECK(e == Approx(e_ref).epsilon(1e-13));
  CHECK(err < 1e-13);
  CHECK(wf->left_wall_force() == Approx(left).epsilon(1e-13));
  CHECK(wf->right_wall_force() == Approx(right).epsilon(1e-13));
}

TEST_CASE("contacts refuse a body that would overlap its own periodic image") {
  // Vertices of one body do not interact, images included: an adipocyte of outer diameter 6
  // (vertices at radius 2, diameter 2) in L_y = 5.5 would overlap its image by 0.5 with no
  // force (the list's own box check, reach 2.3, passes). L_y = 6.5 leaves a gap.
  for (const double L : {5.5, 6.5}) {
    System sys(Box(Vec3::Zero(), Vec3(12.0, L, 12.0), {false, true, true}), 1);
    sys.add_mesh_scaled(icosphere(1), Vec3(6.0, 0.1, 6.0), 2.0, 2.0, 1.1);  // across y = 0
    ContactForce contact(ContactParams{});
    if (L < 6.0)
      CHECK_THROWS_WITH(contact.add_forces(sys, {true, false}),
                        Catch::Matchers::Contains("overlap its own periodic image"));
    else
      CHECK_NOTHROW(contact.add_forces(sys, {true, false}));
  }
}

TEST_CASE("wall forces are minus the gradient of the wall energy (finite differences)") {
  SECTION("sites near both walls, some slightly beyond") {
    System sys = near_walls(120, 31);
    sys.sites().pos[0][0] = -3.05;
    sys.sites().pos[3][0] = 5.04;
    ForceField ff = field_of(std::make_shared<WallForce>(1.3));
    const FdCheck r = fd_check(sys, ff);
    CHECK(r.max_force > 0.1);
    CHECK(r.rel_err < 1e-6);
    report("FD wall", r.rel_err);
  }
  SECTION("narrow box: sites feel both walls at once") {
    System sys(Box(Vec3(2.0, 0.0, 0.0), Vec3(3.5, 6.0, 6.0), {false, true, true}), 32);
    for (int i = 0; i < 40; ++i)
      sys.add_sphere(
          Vec3(2.0 + 1.5 * uniform(32, i, 0), 6.0 * uniform(32, i, 1), 6.0 * uniform(32, i, 2)),
          i % 2 ? 1.1 : 0.9);
    auto wf = std::make_shared<WallForce>(1.0);
    ForceField ff = field_of(wf);
    const FdCheck r = fd_check(sys, ff);
    CHECK(r.max_force > 0.1);
    CHECK(r.rel_err < 1e-6);
    // Reactions on the walls are minus the forces the walls exert.
    CHECK(wf->left_wall_force() + wf->right_wall_force() ==
          Approx(-force_sum(sys)[0]).margin(1e-12));
    report("FD wall (narrow box)", r.rel_err);
  }
}

TEST_CASE("shape forces are minus the gradient of the shape energy (finite differences)") {
  const std::array<std::pair<double, double>, 4> params{
      {{100.0, 1.0}, {1.0, 0.0}, {0.0, 1.0}, {3.7, 0.25}}};
  for (const auto& [eps_v, eps_a] : params) {
    CAPTURE(eps_v, eps_a);
    System sys = shape_system(41);
    ForceField ff = field_of(std::make_shared<ShapeForce>(eps_v, eps_a));
    const double e = ff.compute(sys, {true, false}).energy;
    CHECK(e > 1e-3 * std::max(eps_v, eps_a));
    const FdCheck r = fd_check(sys, ff);
    CHECK(r.max_force > 1e-3 * std::max(eps_v, eps_a));
    CHECK(r.rel_err < 1e-6);
    report("max force", r.max_force);
    char what[80];
    std::snprintf(what, sizeof what, "FD shape eps_v=%g eps_a=%g", eps_v, eps_a);
    report(what, r.rel_err);
  }
}

TEST_CASE("tethers: zero energy at insertion, model energy with minimum image after moves") {
  System sys = tether_system(52);
  TetherForce tf(2.5);
  const double dc = tf.connect_by_mean_degree(sys, 6.0);
  REQUIRE(tf.tethers().size() == 54);
  // The tethered pairs are exactly those closer than d_c.
  const auto c = TetherForce::body_centres(sys);
  int closer = 0, across = 0;
  for (std::size_t a = 0; a < c.size(); ++a)
    for (std::size_t b = a + 1; b < c.size(); ++b)
      closer += image_distance(sys.box(), c[a], c[b]) < dc;
  CHECK(closer == 54);
  for (const Tether& t : tf.tethers()) {
    CHECK(image_distance(sys.box(), c[t.a], c[t.b]) < dc);
    CHECK(t.rest_length == Approx(image_distance(sys.box(), c[t.a], c[t.b])).epsilon(1e-12));
    across += (c[t.a] - c[t.b]).norm() > t.rest_length + 1.0;
  }
  CHECK(across >= 5);
  auto shared = std::make_shared<TetherForce>(tf);
  ForceField ff = field_of(shared);
  CHECK(ff.compute(sys, {true, false}).energy == Approx(0.0).margin(1e-20));
  CHECK(max_force(sys) < 1e-14);
  // After moving the bodies: U = K/2 sum (R_ij - l_ij0)^2, shared equally by the vertices.
  displace_bodies(sys, 0.8, 98);
  const auto c2 = TetherForce::body_centres(sys);
  double e_ref = 0.0;
  for (const Tether& t : tf.tethers()) {
    const double r = image_distance(sys.box(), c2[t.a], c2[t.b]);
    e_ref += 0.5 * 2.5 * (r - t.rest_length) * (r - t.rest_length);
  }
  CHECK(e_ref > 1.0);
  CHECK(ff.compute(sys, {true, false}).energy == Approx(e_ref).epsilon(1e-12));
  for (std::size_t b = 0; b < sys.bodies().size(); ++b) {
    const MeshBody& body = sys.bodies()[b];
    for (int v = 1; v < body.n_vertices(); ++v)
      CHECK((sys.sites().force[body.first_site + v] - sys.sites().force[body.first_site]).norm() ==
            0.0);
  }
}

TEST_CASE("tethers: a mean degree that cannot be met, or a second connect, is refused") {
  System sys = tether_system(52);
  const std::size_t n = sys.bodies().size();
  TetherForce tf(2.5);
  CHECK_THROWS_WITH(tf.connect_by_mean_degree(sys, double(n)),
                    Catch::Contains("is more than " + std::to_string(n - 1)));
  CHECK_THROWS_WITH(tf.connect_by_mean_degree(sys, 0.4 / double(n)),
                    Catch::Contains("gives no tether among " + std::to_string(n)));
  CHECK(tf.tethers().empty());
  tf.connect_by_mean_degree(sys, double(n - 1));  // all pairs
  CHECK(tf.tethers().size() == n * (n - 1) / 2);
  CHECK_THROWS_WITH(tf.connect_by_mean_degree(sys, 2.0), Catch::Contains("already connected"));
  CHECK(tf.tethers().size() == n * (n - 1) / 2);
  tf.clear();
  tf.connect_by_mean_degree(sys, 2.0);
  CHECK(tf.tethers().size() == n);
}

// The paper's heterogeneity (docs/model.md, protocol step 5): tethers whose midpoint (minimum
// image, wrapped into the box) lies in the lower half in z are shortened to (1 - lambda) R,
// the others lengthened to (1 + lambda) R. Which half gets which is checked, not only |l/R - 1|.
TEST_CASE("tether heterogeneity: lower half in z shortened by lambda, upper half lengthened") {
  System sys = tether_system(52);
  TetherForce tf(2.5);
  tf.connect_by_mean_degree(sys, 6.0);
  const double lambda = 0.3;
  tf.apply_heterogeneity(sys, lambda);
  const Box& box = sys.box();
  const auto c = TetherForce::body_centres(sys);
  int lower = 0, upper = 0, across = 0;
  for (const Tether& t : tf.tethers()) {
    const Vec3 d = nearest_image(box, c[t.a], c[t.b]);
    across += std::abs(d.z() - (c[t.a] - c[t.b]).z()) > 1.0;
    double z = std::fmod(c[t.b].z() + 0.5 * d.z() - box.lo()[2], box.length(2));
    if (z < 0.0) z += box.length(2);
    const bool below = z < 0.5 * box.length(2);
    ++(below ? lower : upper);
    CAPTURE(t.a, t.b, z);
    CHECK(t.rest_length == Approx((below ? 1.0 - lambda : 1.0 + lambda) * d.norm()).epsilon(1e-12));
  }
  CHECK(lower >= 5);
  CHECK(upper >= 5);
  CHECK(across >= 3);  // midpoints of tethers across the periodic z boundary are wrapped
}

TEST_CASE("tether forces are minus the gradient of the tether energy (finite differences)") {
  System sys = tether_system(51);
  auto tf = make_tethers(sys, 2.5);
  REQUIRE(tf->tethers().size() == 56);  // 18 bodies x 6 / 2 + 2 manual
  // Some tethers cross the periodic y or z edge; some are stretched, some compressed.
  const auto c = TetherForce::body_centres(sys);
  int across = 0, stretched = 0, compressed = 0;
  for (const Tether& t : tf->tethers()) {
    const Vec3 raw = c[t.a] - c[t.b], d = sys.box().minimum_image(raw);
    across += (raw - d).norm() > 1.0;
    stretched += d.norm() > t.rest_length + 0.1;
    compressed += d.norm() < t.rest_length - 0.1;
  }
  CHECK(across >= 5);
  CHECK(stretched >= 5);
  CHECK(compressed >= 5);
  ForceField ff = field_of(tf);
  const FdCheck r = fd_check(sys, ff);
  CHECK(r.max_force > 1e-2);
  CHECK(r.rel_err < 1e-6);
  report("FD tether", r.rel_err);
}

// A tether joins the image of its partner it was made with (docs/model.md, "Forces"): when a
// component of R_ij passes L/2 it does not jump to the other image, whose pull would have the
// opposite sign. Two bodies 5.5 apart in y (L = 12), l0 = 1.3 x 5.5 = 7.15 > L/2, then 6.5
// apart: the spring still pushes them apart along its own image.
TEST_CASE("a tether keeps its image when a component of R_ij passes half the box") {
  System sys(Box(Vec3::Zero(), Vec3(12.0, 12.0, 12.0), {false, true, true}), 7);
  const MeshShape shape = icosphere(1);
  sys.add_mesh_scaled(shape, Vec3(6.0, 2.0, 6.0), 2.0, 2.0, 1.1);
  sys.add_mesh_scaled(shape, Vec3(6.0, 7.5, 6.0), 2.0, 2.0, 1.1);
  sys.wrap_all();
  const double k = 0.04;
  auto tf = std::make_shared<TetherForce>(k);
  const double l0 = 1.3 * 5.5;
  tf->add(sys, 0, 1, l0);
  CHECK(tf->tethers()[0].periods == Vec3i::Zero());
  const MeshBody& moved = sys.bodies()[1];
  for (int v = 0; v < moved.n_vertices(); ++v)
    sys.sites().pos[moved.first_site + v] += Vec3(0.0, 1.0, 0.0);
  sys.wrap_all();
  const auto c = TetherForce::body_centres(sys);
  REQUIRE(TetherForce::separation(sys.box(), c, tf->tethers()[0])[1] == Approx(-6.5));
  ForceField ff = field_of(tf);
  CHECK(ff.compute(sys, {true, false}).energy ==
        Approx(0.5 * k * (6.5 - l0) * (6.5 - l0)).epsilon(1e-12));
  Vec3 on_first = Vec3::Zero();
  const MeshBody& first = sys.bodies()[0];
  for (int v = 0; v < first.n_vertices(); ++v) on_first += sys.sites().force[first.first_site + v];
  // F_a = -K (R - l0) d / R with d = R_a - R_b = (0, -6.5, 0): -0.026 along y (apart).
  CHECK(on_first[1] == Approx(-k * (l0 - 6.5)).epsilon(1e-10));
  CHECK(std::abs(on_first[0]) + std::abs(on_first[2]) < 1e-12);
  const FdCheck r = fd_check(sys, ff);
  CHECK(r.max_force > 1e-4);
  CHECK(r.rel_err < 1e-6);
}

// ---------------------------------------------------------------------------------------
// Virial

TEST_CASE("virial W_aa equals -dU/d(ln L_a) under an affine stretch, for every term") {
  SECTION("contact, periodic box") {
    System sys = random_spheres(300, 0.5, false, 61);
    virial_error(
        sys, [] { return field_of(std::make_shared<ContactForce>(cohesive_params())); },
        "virial contact (periodic)");
  }
  SECTION("contact, walled box with adipocytes") {
    System sys = mixed_system(2, 80, 4.6, 0.4, 62);
    virial_error(
        sys, [] { return field_of(std::make_shared<ContactForce>(cohesive_params())); },
        "virial contact (walled, mixed)");
  }
  SECTION("walls") {
    System sys = near_walls(120, 63);
    virial_error(
        sys, [] { return field_of(std::make_shared<WallForce>(1.0)); }, "virial wall");
  }
  SECTION("shape") {
    System sys = shape_system(64);
    virial_error(
        sys, [] { return field_of(std::make_shared<ShapeForce>(100.0, 1.0)); }, "virial shape");
  }
  SECTION("tethers") {
    System sys = tether_system(65);
    auto tf = make_tethers(sys, 2.5);
    virial_error(
        sys, [&] { return field_of(std::make_shared<TetherForce>(*tf)); }, "virial tether");
  }
}

// ---------------------------------------------------------------------------------------
// Momentum

TEST_CASE("contact, shape and tether forces sum to zero at random configurations") {
  System sys = mixed_system(2, 80, 4.6, 0.4, 71);
  ContactParams p = cohesive_params();
  p.eps_cv = 0.7;
  for (auto f : std::vector<std::shared_ptr<Force>>{std::make_shared<ContactForce>(p),
                                                    std::make_shared<ShapeForce>(100.0, 1.0)}) {
    ForceField ff = field_of(f);
    ff.compute(sys);
    CAPTURE(f->name());
    REQUIRE(max_force(sys) > 0.1);
    CHECK(force_sum(sys).norm() < 1e-12 * max_force(sys));
    report(("momentum " + f->name()).c_str(), force_sum(sys).norm() / max_force(sys));
  }
  System tsys = tether_system(72);
  auto tf = make_tethers(tsys, 2.5);
  ForceField ff = field_of(tf);
  ff.compute(tsys);
  REQUIRE(max_force(tsys) > 1e-2);
  CHECK(force_sum(tsys).norm() < 1e-12 * max_force(tsys));
  report("momentum tether", force_sum(tsys).norm() / max_force(tsys));
}

// ---------------------------------------------------------------------------------------
// Shape-energy Hessian

namespace {
// Eigenvalues (ascending) of the central-difference Hessian of the analytic gradient.
Eigen::VectorXd shape_hessian_eigenvalues(const MeshBody& body, std::vector<Vec3> x, double eps_v,
                                          double eps_a, double h = 1e-6) {
  const int n = int(x.size()), dof = 3 * n;
  Eigen::MatrixXd H(dof, dof);
  std::vector<Vec3> gp(n), gm(n);
  for (int v = 0; v < n; ++v)
    for (int a = 0; a < 3; ++a) {
      const double x0 = x[v][a], xp = x0 + h, xm = x0 - h;
      std::fill(gp.begin(), gp.end(), Vec3::Zero());
      std::fill(gm.begin(), gm.end(), Vec3::Zero());
      x[v][a] = xp;
      body_shape_energy(body, x.data(), eps_v, eps_a, gp.data());
      x[v][a] = xm;
      body_shape_energy(body, x.data(), eps_v, eps_a, gm.data());
      x[v][a] = x0;
      for (int w = 0; w < n; ++w)
        for (int b = 0; b < 3; ++b) H(3 * w + b, 3 * v + a) = (gp[w][b] - gm[w][b]) / (xp - xm);
    }
  const Eigen::MatrixXd S = 0.5 * (H + H.transpose());
  CHECK((H - H.transpose()).cwiseAbs().maxCoeff() < 1e-7 * H.cwiseAbs().maxCoeff());
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(S, Eigen::EigenvaluesOnly);
  return es.eigenvalues();
}

MeshBody body_at_own_reference(const MeshShape& shape, const std::vector<Vec3>& x) {
  MeshBody body{shape.topology, 0, {}, mesh_volume(*shape.topology, x.data())};
  for (int k = 0; k < shape.topology->n_faces(); ++k)
    body.ref_area.push_back(face_area(*shape.topology, x.data(), k));
  return body;
}

int count_below(const Eigen::VectorXd& ev, double rel) {
  int n = 0;
  for (int k = 0; k < ev.size(); ++k) n += std::abs(ev[k]) < rel * ev[ev.size() - 1];
  return n;
}
}  // namespace

TEST_CASE("shape Hessian at U = 0: perturbed icosphere has 45 zero modes, perfect icosphere 46") {
  const MeshShape shape = icosphere(1);
  const double eps_v = 100.0, eps_a = 1.0, thr = 1e-8;
  SECTION("randomly perturbed icosphere") {
    std::vector<Vec3> x = shape.vertices;
    for (int v = 0; v < 42; ++v)
      x[v] = 2.0 * x[v] +
             0.15 * Vec3(uniform(81, v, 0) - 0.5, uniform(81, v, 1) - 0.5, uniform(81, v, 2) - 0.5);
    const MeshBody body = body_at_own_reference(shape, x);
    std::vector<Vec3> g(42, Vec3::Zero());
    CHECK(body_shape_energy(body, x.data(), eps_v, eps_a, g.data()) == 0.0);
    const Eigen::VectorXd ev = shape_hessian_eigenvalues(body, x, eps_v, eps_a);
    const double top = ev[125];
    INFO("lambda_44 / lambda_max = " << ev[44] / top
                                     << ", lambda_45 / lambda_max = " << ev[45] / top);
    CHECK(count_below(ev, thr) == 45);
    CHECK(ev[45] / top > 1e-4);
    CHECK(ev[0] > -thr * top);
    report("perturbed: |lambda_45| / lambda_max (largest zero mode)", std::abs(ev[44]) / top);
    report("perturbed: lambda_46 / lambda_max (smallest non-zero)", ev[45] / top);
    report("perturbed: gap lambda_46 / |lambda_45|", ev[45] / std::abs(ev[44]));
  }
  SECTION("perfect icosphere") {
    std::vector<Vec3> x = shape.vertices;
    for (Vec3& v : x) v *= 2.0;
    const MeshBody body = body_at_own_reference(shape, x);
    const Eigen::VectorXd ev = shape_hessian_eigenvalues(body, x, eps_v, eps_a);
    const double top = ev[125];
    INFO("lambda_45 / lambda_max = " << ev[45] / top
                                     << ", lambda_46 / lambda_max = " << ev[46] / top);
    CHECK(count_below(ev, thr) == 46);
    CHECK(ev[46] / top > 1e-4);
    report("perfect: |lambda_46| / lambda_max (largest zero mode)", std::abs(ev[45]) / top);
    report("perfect: lambda_47 / lambda_max (smallest non-zero)", ev[46] / top);
    report("perfect: gap lambda_47 / |lambda_46|", ev[46] / std::abs(ev[45]));
  }
}

// ---------------------------------------------------------------------------------------
// Bad input

TEST_CASE("bad input is refused with a message naming the problem") {
  System sys(cube(10.0, true), 1);
  CHECK_THROWS_WITH(sys.add_sphere(Vec3(5, 5, 5), 0.0),
                    Contains("diameter = 0") && Contains("> 0"));
  CHECK_THROWS_WITH(sys.add_sphere(Vec3(5, 5, 5), -1.0), Contains("diameter = -1"));
  CHECK_THROWS_WITH(sys.add_sphere(Vec3(-0.1, 5, 5), 1.0), Contains("outside the walls"));
  CHECK_THROWS_WITH(sys.add_sphere(Vec3(10.5, 5, 5), 1.0), Contains("x = 10.5"));
  CHECK(sys.n_sites() == 0);

  ContactParams p;
  p.alpha = 0.2;
  p.beta = 0.2;
  CHECK_THROWS_WITH(ContactForce(p), Contains("beta = 0.2 must be smaller than alpha = 0.2"));
  p.beta = 0.3;
  CHECK_THROWS_WITH(ContactForce(p), Contains("smaller than alpha"));
  p.beta = -0.01;
  CHECK_THROWS_WITH(ContactForce(p), Contains("beta = -0.01 must be >= 0"));
  {
    ContactParams q;
    q.alpha_cv = 0.1;
    q.beta_cv = 0.1;
    CHECK_THROWS_WITH(ContactForce(q),
                      Contains("adhesion: beta_cv = 0.1 must be smaller than alpha_cv = 0.1"));
    q.beta_cv = -0.5;
    CHECK_THROWS_WITH(ContactForce(q), Contains("beta_cv = -0.5 must be >= 0"));
  }
  p.beta = 0.01;
  CHECK_NOTHROW(ContactForce(p));

  CHECK_THROWS_WITH(Dynamics(0.0), Contains("dt = 0 must be > 0"));
  CHECK_THROWS_WITH(Dynamics(-0.05), Contains("dt = -0.05 must be > 0"));
  Dynamics dyn(0.05);
  CHECK_THROWS_WITH(dyn.set_dt(0.0), Contains("dt = 0"));
  CHECK_THROWS_WITH(dyn.set_dt(std::numeric_limits<double>::infinity()),
                    Contains("dt = inf must be finite"));
  CHECK_THROWS_WITH(Dynamics(std::numeric_limits<double>::infinity()),
                    Contains("dt = inf must be finite"));
  CHECK(dyn.dt() == 0.05);
  CHECK_THROWS_WITH(Method::active({0}, 0.2, 1.0, -1.0), Contains("tau_p = -1 must be >= 0"));
  CHECK_NOTHROW(Method::active({0}, 0.2, 1.0, 0.0));

  const MeshShape shape = icosphere(1);
  CHECK_THROWS_WITH(sys.add_mesh_scaled(shape, Vec3(9.0, 5, 5), 2.0, 2.0, 1.1),
                    Contains("vertex") && Contains("outside the walls"));
  std::vector<Vec3> mirrored;
  for (const Vec3& v : shape.vertices)
    mirrored.push_back(Vec3(5 - 2 * v[0], 5 + 2 * v[1], 5 + 2 * v[2]));
  const std::vector<double> area(80, 0.2);
  CHECK_THROWS_WITH(sys.add_mesh(shape.topology, mirrored, 2.0, area, 30.0),
                    Contains("not positive") && Contains("oriented outward"));
  CHECK(sys.n_sites() == 0);
  CHECK(sys.bodies().empty());

  CHECK_THROWS_WITH(TetherForce(-1.0), Contains("K_ecm = -1 must be >= 0"));
  TetherForce tf(1.0);
  CHECK_THROWS_WITH(tf.set_stiffness(-2.0), Contains("K_ecm = -2"));
  sys.add_mesh_scaled(shape, Vec3(3, 5, 5), 2.0, 2.0, 1.1);
  sys.add_mesh_scaled(shape, Vec3(7, 5, 5), 2.0, 2.0, 1.1);
  CHECK_THROWS_WITH(tf.add(sys, 1, 1, 1.0), Contains("cannot be tethered to itself"));
  CHECK_THROWS_WITH(tf.add(sys, 0, 2, 1.0), Contains("outside [0, 2)"));
  CHECK(tf.tethers().empty());
}

// ---------------------------------------------------------------------------------------
// Shape kernel (faces in vector lanes) against a plain one-face-at-a-time sum

namespace {
// U_i and its gradient summed face by face with Eigen's vector operations: the textbook form
// of ShapeKernel::evaluate (docs/model.md, "Bodies").
double plain_shape_energy(const MeshBody& body, const Vec3* x, double eps_v, double eps_a,
                          Vec3* grad) {
  const MeshTopology& topo = *body.topology;
  const double dv = 1.0 - mesh_volume(topo, x) / body.ref_volume;
  double energy = 0.5 * eps_v * dv * dv;
  add_volume_gradient(topo, x, -eps_v * dv / body.ref_volume, grad);
  for (int k = 0; k < topo.n_faces(); ++k) {
    const auto& f = topo.faces()[k];
    const Vec3 &a = x[f[0]], &b = x[f[1]], &c = x[f[2]];
    const Vec3 n = (b - a).cross(c - a);
    const double da = 1.0 - 0.5 * n.norm() / body.ref_area[k];
    energy += 0.5 * eps_a * da * da;
    if (n.norm() == 0.0) continue;
    const double scale = -eps_a * da / body.ref_area[k] * 0.5;
    grad[f[0]] += scale * (b - c).cross(n.normalized());
    grad[f[1]] += scale * (c - a).cross(n.normalized());
    grad[f[2]] += scale * (a - b).cross(n.normalized());
  }
  return energy;
}
}  // namespace

TEST_CASE("shape kernel: equals the plain face-by-face sum, corner lists in face order") {
  const MeshShape shape = icosphere(1);
  const MeshTopology& topo = *shape.topology;
  // Every (face, corner) once, grouped by vertex, faces increasing within a vertex.
  REQUIRE(topo.corner_offsets().size() == 43);
  REQUIRE(topo.corners().size() == std::size_t(3 * topo.n_faces()));
  for (int v = 0; v < 42; ++v)
    for (int m = topo.corner_offsets()[v]; m < topo.corner_offsets()[v + 1]; ++m) {
      const auto [f, corner] = topo.corners()[m];
      CHECK(topo.faces()[f][corner] == v);
      if (m > topo.corner_offsets()[v]) CHECK(topo.corners()[m - 1].first < f);
    }
  ShapeKernel kernel;
  double worst_e = 0.0, worst_g = 0.0;
  for (int trial = 0; trial < 200; ++trial) {
    // A deformed, shifted body against a reference of another shape, so that every term is
    // non-zero; trial 0 has a degenerate face (two vertices at one point: zero area).
    std::vector<Vec3> x = shape.vertices, ref = shape.vertices;
    const double spread = 0.05 + 0.3 * uniform(90, trial, 99);
    for (int v = 0; v < 42; ++v) {
      const Vec3 noise(uniform(91, trial * 42 + v, 0) - 0.5, uniform(91, trial * 42 + v, 1) - 0.5,
                       uniform(91, trial * 42 + v, 2) - 0.5);
      x[v] = 3.0 * x[v] + spread * noise + Vec3(100.0 * trial, -7.0, 0.25);
      ref[v] = 2.9 * ref[v] - 0.5 * spread * noise;
    }
    if (trial == 0) x[topo.faces()[5][1]] = x[topo.faces()[5][0]];
    MeshBody body = body_at_own_reference(shape, ref);
    const double eps_v = 50.0 + trial, eps_a = 0.5 + 0.01 * trial;
    std::vector<Vec3> g_ref(42, Vec3::Zero()), g(42, Vec3::Constant(7.0));
    const double e_ref = plain_shape_energy(body, x.data(), eps_v, eps_a, g_ref.data());
    const double e = kernel.evaluate(body, x.data(), eps_v, eps_a, g.data());
    double g_scale = 0.0, g_diff = 0.0;
    for (int v = 0; v < 42; ++v) {
      g_scale = std::max(g_scale, g_ref[v].norm());
      g_diff = std::max(g_diff, (g[v] - g_ref[v]).norm());
    }
    INFO("trial " << trial << ": energy " << e << " against " << e_ref);
    REQUIRE(e_ref > 0.0);
    REQUIRE(g_scale > 0.0);
    worst_e = std::max(worst_e, std::abs(e - e_ref) / e_ref);
    worst_g = std::max(worst_g, g_diff / g_scale);
    // body_shape_energy adds the same gradient to what it is given.
    std::vector<Vec3> g_add(42, Vec3::Constant(1.0));
    CHECK(body_shape_energy(body, x.data(), eps_v, eps_a, g_add.data()) == e);
    for (int v = 0; v < 42; ++v) CHECK(g_add[v] == (Vec3::Constant(1.0) + g[v]).eval());
  }
  report("shape kernel: largest relative energy difference", worst_e);
  report("shape kernel: largest gradient difference / largest gradient", worst_g);
  CHECK(worst_e < 1e-13);
  CHECK(worst_g < 1e-13);
}
