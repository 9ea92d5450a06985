#include "forces/contact_force.hpp"

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
  const double x = 1.0 - r / s;
  return {eps / s * x, 0.5 * eps * x * x};
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
  params_.validate();
  CutoffRule rule;
  rule.factor[0][0] = params_.beta > 0.0 ? 1.0 + params_.alpha : 1.0;
  list_.set_cutoff_rule(rule);
}

ForceResult ContactForce::add_forces(System& sys, const ForceFlags& flags) {
  list_.update(sys);
  Sites& s = sys.sites();
  const std::size_t n = s.size();
  const Box& box = sys.box();
  const Vec3 len = box.lengths(), half = 0.5 * len;
  const bool py = box.periodic(1), pz = box.periodic(2), px = box.periodic(0);
  const double eps[2][2] = {{params_.eps_cc, params_.eps_cv}, {params_.eps_cv, params_.eps_vv}};
  const double alpha = params_.alpha, beta = params_.beta;
  const bool cohesive = beta > 0.0;
  const bool want_e = flags.energy, want_v = flags.virial;
  if (want_e) site_energy_.assign(n, 0.0);
  if (want_v) site_virial_.assign(n, Vec3::Zero());

#pragma omp parallel for schedule(dynamic, 128)
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 ri = s.pos[i];
    const double di = s.diameter[i];
    const int ki = int(s.kind[i]);
    const int* nb = list_.neighbors(i);
    const int m = list_.count(i);
    Vec3 fi = Vec3::Zero(), wi = Vec3::Zero();
    double ei = 0.0;
    for (int k = 0; k < m; ++k) {
      const int j = nb[k];
      Vec3 d = ri - s.pos[j];
      if (px) d[0] -= len[0] * std::round(d[0] / len[0]);
      if (py) d[1] += d[1] > half[1] ? -len[1] : (d[1] < -half[1] ? len[1] : 0.0);
      if (pz) d[2] += d[2] > half[2] ? -len[2] : (d[2] < -half[2] ? len[2] : 0.0);
      const double r2 = d.squaredNorm();
      const int kj = int(s.kind[j]);
      const double sig = 0.5 * (di + s.diameter[j]);
      const bool cc = ki == 0 && kj == 0 && cohesive;
      const double rc = cc ? (1.0 + alpha) * sig : sig;
      if (r2 >= rc * rc) continue;
      const double r = std::sqrt(r2);
      const PairEval pe =
          cc ? cohesive_spring(r, sig, eps[0][0], alpha, beta) : linear_spring(r, sig, eps[ki][kj]);
      Vec3 dir;
      if (r > 1e-12 * sig) {
        dir = d / r;
      } else {
        // Coincident sites: a fixed direction, opposite for the two partners.
        dir = Vec3(int(i) < j ? 1.0 : -1.0, 0.0, 0.0);
      }
      const Vec3 f = pe.force * dir;
      fi += f;
      if (want_e) ei += 0.5 * pe.energy;
      if (want_v) wi += 0.5 * d.cwiseProduct(f);
    }
    s.force[i] += fi;
    if (want_e) site_energy_[i] = ei;
    if (want_v) site_virial_[i] = wi;
  }
  ForceResult out;
  if (want_e) out.energy = deterministic_sum(n, 0.0, [&](std::size_t i) { return site_energy_[i]; });
  if (want_v)
    out.virial = deterministic_sum(n, Vec3(Vec3::Zero()), [&](std::size_t i) { return site_virial_[i]; });
  return out;
}

}  // namespace invasim
