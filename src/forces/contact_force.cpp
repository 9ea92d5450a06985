#include "forces/contact_force.hpp"
#include "core/parallel.hpp"

#include <cmath>

#include "core/deterministic_sum.hpp"
#include "core/errors.hpp"

namespace invasim {

void ContactParams::validate() const {
  require_positive("eps_cc", eps_cc);
  require_positive("eps_cv", eps_cv);
  require_positive("eps_vv", eps_vv);
  require_non_negative("alpha", alpha);
  require_non_negative("beta", beta);
  require_non_negative("skin", skin);
  if (beta > 0.0 && !(beta < alpha))
    fail_input("cohesion: beta = ", beta, " must be smaller than alpha = ", alpha,
               " (attraction peaks at r_b = (1+beta)s inside the range r_a = (1+alpha)s)");
}

PairEval linear_spring(double r, double s, double eps) {
  if (r >= s) return {0.0, 0.0};
  const double inv_s = 1.0 / s;
  const double x = 1.0 - r * inv_s;
  return {eps * inv_s * x, 0.5 * eps * x * x};
}

PairEval cohesive_spring(double r, double s, double eps, double alpha, double beta) {
  if (beta <= 0.0) return linear_spring(r, s, eps);
  const double ra = (1.0 + alpha) * s, rb = (1.0 + beta) * s;
  if (r > ra) return {0.0, 0.0};
  if (r > rb) {
    const double k = eps / (s * s) * beta / (alpha - beta);  // slope of the attractive branch
    return {k * (r - ra), -0.5 * k * (ra - r) * (ra - r)};
  }
  const double x = 1.0 - r / s;
  return {eps / s * x, 0.5 * eps * (x * x - alpha * beta)};
}

ContactForce::ContactForce(const ContactParams& params) : params_(params), list_(params.skin) {
  set_params(params);
}

void ContactForce::set_params(const ContactParams& params) {
  params.validate();
  params_ = params;
  list_ = VerletList(params_.skin);
  CutoffRule rule;
  rule.factor[0][0] = params_.beta > 0.0 ? 1.0 + params_.alpha : 1.0;
  list_.set_cutoff_rule(rule);
}

ForceResult ContactForce::add_forces(System& sys, const ForceFlags& flags) {
  list_.update(sys);
  Sites& s = sys.sites();
  const std::size_t n = s.size();
  const Box& box = sys.box();
  const MinimumImage image(box);
  const double eps[2][2] = {{params_.eps_cc, params_.eps_cv}, {params_.eps_cv, params_.eps_vv}};
  const double alpha = params_.alpha, beta = params_.beta;
  const bool cohesive = beta > 0.0;
  const bool want_e = flags.energy, want_v = flags.virial;
  if (want_e) site_energy_.assign(n, 0.0);
  if (want_v) site_virial_.assign(n, Vec3::Zero());
  const Vec3* pos = s.pos.data();
  const double* diam = s.diameter.data();
  const SiteKind* kind = s.kind.data();

#pragma omp parallel for schedule(dynamic, 128) if (parallel_heavy(n))
  for (std::size_t i = 0; i < n; ++i) {
    const double xi = pos[i][0], yi = pos[i][1], zi = pos[i][2];
    const double di = diam[i];
    const int ki = int(kind[i]);
    const int* nb = list_.neighbors(i);
    const int m = list_.count(i);
    double fx = 0.0, fy = 0.0, fz = 0.0, ei = 0.0;
    Vec3 wi = Vec3::Zero();
    for (int k = 0; k < m; ++k) {
      const int j = nb[k];
      const double dx = image.x(xi - pos[j][0]), dy = image.y(yi - pos[j][1]),
                   dz = image.z(zi - pos[j][2]);
      const double r2 = dx * dx + dy * dy + dz * dz;
      const double sig = 0.5 * (di + diam[j]);
      const int kj = int(kind[j]);
      const bool cc = cohesive && (ki | kj) == 0;
      const double rc = cc ? (1.0 + alpha) * sig : sig;
      if (r2 >= rc * rc) continue;
      const double r = std::sqrt(r2);
      const PairEval pe =
          cc ? cohesive_spring(r, sig, eps[0][0], alpha, beta) : linear_spring(r, sig, eps[ki][kj]);
      double ux, uy, uz;
      if (r > 1e-12 * sig) {
        const double inv = 1.0 / r;
        ux = dx * inv, uy = dy * inv, uz = dz * inv;
      } else {
        // Coincident sites: a fixed direction, opposite for the two partners.
        ux = int(i) < j ? 1.0 : -1.0, uy = 0.0, uz = 0.0;
      }
      fx += pe.force * ux;
      fy += pe.force * uy;
      fz += pe.force * uz;
      if (want_e) ei += 0.5 * pe.energy;
      if (want_v) wi += 0.5 * pe.force * Vec3(dx * ux, dy * uy, dz * uz);
    }
    s.force[i] += Vec3(fx, fy, fz);
    if (want_e) site_energy_[i] = ei;
    if (want_v) site_virial_[i] = wi;
  }
  ForceResult out;
  if (want_e)
    out.energy = deterministic_sum(n, 0.0, [&](std::size_t i) { return site_energy_[i]; });
  if (want_v)
    out.virial =
        deterministic_sum(n, Vec3(Vec3::Zero()), [&](std::size_t i) { return site_virial_[i]; });
  return out;
}

}  // namespace invasim
