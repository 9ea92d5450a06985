#include "forces/tether_force.hpp"

#include <algorithm>

#include "core/errors.hpp"
#include "core/parallel.hpp"
#include "core/team_barrier.hpp"
#include "mesh/geometry.hpp"

namespace invasim {

TetherForce::TetherForce(double stiffness) : stiffness_(stiffness) {
  require_non_negative("K_ecm", stiffness);
}

void TetherForce::set_stiffness(double k) {
  require_non_negative("K_ecm", k);
  stiffness_ = k;
}

namespace {

// Refuses a tether between bodies that do not exist, a body and itself, or a negative rest
// length.
void check_tether(const System& sys, int a, int b, double rest_length) {
  const int nb = int(sys.bodies().size());
  if (a < 0 || a >= nb || b < 0 || b >= nb)
    fail_input("tether (", a, ", ", b, "): body index outside [0, ", nb, ")");
  if (a == b) fail_input("tether (", a, ", ", b, "): a body cannot be tethered to itself");
  if (!(rest_length >= 0.0))
    fail_input("tether (", a, ", ", b, "): rest length ", rest_length, " must be >= 0");
}

// The unwrapped vertex centroid of body b.
Vec3 body_centre(const System& sys, int b) {
  std::vector<Vec3> x(sys.bodies()[b].n_vertices());
  sys.body_vertices(b, x.data());
  return vertex_centroid(int(x.size()), x.data());
}

}  // namespace

std::vector<Vec3> TetherForce::body_centres(const System& sys) {
  std::vector<Vec3> c(sys.bodies().size());
  for (std::size_t b = 0; b < c.size(); ++b) c[b] = body_centre(sys, int(b));
  return c;
}

void TetherForce::add(const System& sys, int a, int b, double rest_length) {
  check_tether(sys, a, b, rest_length);
  tethers_.push_back(
      {a, b, rest_length, sys.box().nearest_periods(body_centre(sys, a) - body_centre(sys, b))});
}

void TetherForce::add(const System& sys, int a, int b, double rest_length, const Vec3i& periods) {
  check_tether(sys, a, b, rest_length);
  for (int axis = 0; axis < 3; ++axis)
    if (!sys.box().periodic(axis) && periods[axis] != 0)
      fail_input("tether (", a, ", ", b, "): ", periods[axis], " periods along the walled axis ",
                 axis);
  tethers_.push_back({a, b, rest_length, periods});
}

double TetherForce::connect_by_mean_degree(const System& sys, double mean_degree) {
  require_positive("tether mean degree", mean_degree);
  if (!tethers_.empty())
    fail_input("tethers: already connected (", tethers_.size(),
               " tethers): a second connect would tether the same pairs twice, doubling their "
               "stiffness; clear() them first");
  const std::vector<Vec3> c = body_centres(sys);
  const int nb = int(c.size());
  if (nb < 2) fail_input("tethers: need at least two adipocytes to tether, the System has ", nb);
  if (mean_degree > nb - 1)
    fail_input("tethers: mean degree ", mean_degree, " is more than ", nb - 1,
               ", the degree of every adipocyte when all ", nb, " are tethered to each other");
  struct Pair {
    double r;
    int a, b;
    Vec3i periods;
  };
  std::vector<Pair> pairs;
  for (int a = 0; a < nb; ++a)
    for (int b = a + 1; b < nb; ++b) {
      const Vec3i n = sys.box().nearest_periods(c[a] - c[b]);
      pairs.push_back({sys.box().minus_periods(c[a] - c[b], n).norm(), a, b, n});
    }
  std::sort(pairs.begin(), pairs.end(), [](const Pair& p, const Pair& q) {
    return p.r < q.r || (p.r == q.r && (p.a < q.a || (p.a == q.a && p.b < q.b)));
  });
  const std::size_t m = std::min(pairs.size(), std::size_t(std::llround(0.5 * mean_degree * nb)));
  if (m == 0)
    fail_input("tethers: mean degree ", mean_degree, " gives no tether among ", nb,
               " adipocytes (mean degree x adipocytes / 2 rounds to 0); at least ", 1.0 / nb);
  for (std::size_t k = 0; k < m; ++k)
    add(sys, pairs[k].a, pairs[k].b, pairs[k].r, pairs[k].periods);
  return m < pairs.size() ? 0.5 * (pairs[m - 1].r + pairs[m].r) : pairs[m - 1].r;
}

void TetherForce::apply_heterogeneity(const System& sys, double lambda) {
  if (!(lambda >= 0.0 && lambda <= 1.0)) fail_input("lambda = ", lambda, " must be in [0, 1]");
  const std::vector<Vec3> c = body_centres(sys);
  const Box& box = sys.box();
  const double z_mid = box.lo()[2] + 0.5 * box.length(2);
  for (Tether& t : tethers_) {
    const Vec3 d = separation(box, c, t);
    Vec3 mid = c[t.b] + 0.5 * d;
    Vec3i img = Vec3i::Zero();
    box.wrap(mid, img);
    t.rest_length = (mid[2] < z_mid ? 1.0 - lambda : 1.0 + lambda) * d.norm();
  }
}

Vec3 TetherForce::tether_force(const Box& box, const Tether& t, double* stretch) const {
  const Vec3 d = separation(box, centres_, t);
  const double r = d.norm();
  *stretch = r - t.rest_length;
  return r > 0.0 ? Vec3(-stiffness_ * *stretch / r * d) : Vec3(Vec3::Zero());
}

void TetherForce::prepare_team(System& sys, const ForceFlags&) {
  const std::size_t nb = sys.bodies().size();
  centres_.resize(nb);
  body_start_.assign(nb + 1, 0);
  for (const Tether& t : tethers_) {
    ++body_start_[t.a + 1];
    ++body_start_[t.b + 1];
  }
  for (std::size_t b = 0; b < nb; ++b) body_start_[b + 1] += body_start_[b];
  body_tethers_.resize(body_start_[nb]);
  std::vector<int> fill(body_start_.begin(), body_start_.end() - 1);
  for (std::size_t k = 0; k < tethers_.size(); ++k) {
    body_tethers_[fill[tethers_[k].a]++] = int(k) + 1;
    body_tethers_[fill[tethers_[k].b]++] = -(int(k) + 1);
  }
}

ForceResult TetherForce::add_forces_team(System& sys, const ForceFlags& flags) {
  ForceResult out;
  if (tethers_.empty()) return out;  // no forces written: no barrier needed
  const auto& bodies = sys.bodies();
  const int nb = int(bodies.size());
  thread_local std::vector<Vec3> x;
#pragma omp for schedule(static) nowait
  for (int b = 0; b < nb; ++b) {
    x.resize(bodies[b].n_vertices());
    sys.body_vertices(b, x.data());
    centres_[b] = vertex_centroid(int(x.size()), x.data());
  }
  team_barrier();
  // Each body sums the forces of its tethers in tether order (as a serial loop over the
  // tethers would) and shares the total equally among its vertices.
  Sites& s = sys.sites();
#pragma omp for schedule(static) nowait
  for (int b = 0; b < nb; ++b) {
    Vec3 body_force = Vec3::Zero();
    for (int q = body_start_[b]; q < body_start_[b + 1]; ++q) {
      const int k = body_tethers_[q];
      double stretch;
      const Vec3 f = tether_force(sys.box(), tethers_[std::abs(k) - 1], &stretch);
      if (k > 0)
        body_force += f;
      else
        body_force -= f;
    }
    const Vec3 share = body_force / double(bodies[b].n_vertices());
    for (int v = 0; v < bodies[b].n_vertices(); ++v) s.force[sys.body_slot(b, v)] += share;
  }
  team_barrier();
  if (!team_leader() || !(flags.energy || flags.virial)) return out;
  for (const Tether& t : tethers_) {  // few tethers: a serial, fixed-order loop
    double stretch;
    const Vec3 f = tether_force(sys.box(), t, &stretch);
    const Vec3 d = separation(sys.box(), centres_, t);
    out.energy += 0.5 * stiffness_ * stretch * stretch;
    out.virial += d.cwiseProduct(f);
  }
  if (!flags.energy) out.energy = 0.0;
  if (!flags.virial) out.virial.setZero();
  return out;
}

}  // namespace invasim
