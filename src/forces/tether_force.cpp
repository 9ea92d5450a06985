#include "forces/tether_force.hpp"

#include <algorithm>

#include "core/errors.hpp"
#include "mesh/geometry.hpp"

namespace invasim {

TetherForce::TetherForce(double stiffness) : stiffness_(stiffness) {
  require_non_negative("K_ecm", stiffness);
}

void TetherForce::set_stiffness(double k) {
  require_non_negative("K_ecm", k);
  stiffness_ = k;
}

std::vector<Vec3> TetherForce::body_centres(const System& sys) {
  std::vector<Vec3> c(sys.bodies().size());
  std::vector<Vec3> x;
  for (std::size_t b = 0; b < c.size(); ++b) {
    x.resize(sys.bodies()[b].n_vertices());
    sys.body_vertices(int(b), x.data());
    c[b] = vertex_centroid(int(x.size()), x.data());
  }
  return c;
}

void TetherForce::add(const System& sys, int a, int b, double rest_length) {
  const int nb = int(sys.bodies().size());
  if (a < 0 || a >= nb || b < 0 || b >= nb)
    fail_input("tether (", a, ", ", b, "): body index outside [0, ", nb, ")");
  if (a == b) fail_input("tether (", a, ", ", b, "): a body cannot be tethered to itself");
  if (!(rest_length >= 0.0))
    fail_input("tether (", a, ", ", b, "): rest length ", rest_length, " must be >= 0");
  tethers_.push_back({a, b, rest_length});
}

double TetherForce::connect_by_mean_degree(const System& sys, double mean_degree) {
  require_positive("tether mean degree", mean_degree);
  const std::vector<Vec3> c = body_centres(sys);
  const int nb = int(c.size());
  struct Pair {
    double r;
    int a, b;
  };
  std::vector<Pair> pairs;
  for (int a = 0; a < nb; ++a)
    for (int b = a + 1; b < nb; ++b)
      pairs.push_back({sys.box().minimum_image(c[a] - c[b]).norm(), a, b});
  std::sort(pairs.begin(), pairs.end(), [](const Pair& p, const Pair& q) {
    return p.r < q.r || (p.r == q.r && (p.a < q.a || (p.a == q.a && p.b < q.b)));
  });
  const std::size_t m = std::min(pairs.size(), std::size_t(std::llround(0.5 * mean_degree * nb)));
  if (m == 0) fail_input("tethers: need at least two adipocytes to tether");
  for (std::size_t k = 0; k < m; ++k) add(sys, pairs[k].a, pairs[k].b, pairs[k].r);
  return m < pairs.size() ? 0.5 * (pairs[m - 1].r + pairs[m].r) : pairs[m - 1].r;
}

void TetherForce::apply_heterogeneity(const System& sys, double lambda) {
  if (!(lambda >= 0.0 && lambda <= 1.0)) fail_input("lambda = ", lambda, " must be in [0, 1]");
  const std::vector<Vec3> c = body_centres(sys);
  const Box& box = sys.box();
  const double z_mid = box.lo()[2] + 0.5 * box.length(2);
  for (Tether& t : tethers_) {
    const Vec3 d = box.minimum_image(c[t.a] - c[t.b]);
    Vec3 mid = c[t.b] + 0.5 * d;
    Vec3i img = Vec3i::Zero();
    box.wrap(mid, img);
    t.rest_length = (mid[2] < z_mid ? 1.0 - lambda : 1.0 + lambda) * d.norm();
  }
}

ForceResult TetherForce::add_forces(System& sys, const ForceFlags& flags) {
  ForceResult out;
  if (tethers_.empty()) return out;
  const std::vector<Vec3> c = body_centres(sys);
  std::vector<Vec3> body_force(c.size(), Vec3::Zero());
  for (const Tether& t : tethers_) {  // few tethers: a serial, fixed-order loop
    const Vec3 d = sys.box().minimum_image(c[t.a] - c[t.b]);
    const double r = d.norm();
    const double stretch = r - t.rest_length;
    const Vec3 f = r > 0.0 ? Vec3(-stiffness_ * stretch / r * d) : Vec3(Vec3::Zero());
    body_force[t.a] += f;
    body_force[t.b] -= f;
    out.energy += 0.5 * stiffness_ * stretch * stretch;
    out.virial += d.cwiseProduct(f);
  }
  Sites& s = sys.sites();
  const auto& bodies = sys.bodies();
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const Vec3 share = body_force[b] / double(bodies[b].n_vertices());
    for (int v = 0; v < bodies[b].n_vertices(); ++v) s.force[bodies[b].first_site + v] += share;
  }
  if (!flags.energy) out.energy = 0.0;
  if (!flags.virial) out.virial.setZero();
  return out;
}

}  // namespace invasim
