#include "forces/contact_force.hpp"
#include "core/parallel.hpp"

#include <omp.h>

#include <algorithm>
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

namespace {

// The constants of pair (i, j) on the branch of separation^2 r2 (repulsive unless the pair is
// cohesive and r2 > rb2), with the pair's cutoff^2 and coincidence threshold^2.
struct PairBranch {
  double rc2, tiny2, c, d, r0, e0;
};

// The constants of pair (i, j) read from the class table (few distinct (kind, diameter)); the
// branch's constants are loaded at a computed index (see PairTable).
struct TablePairs {
  const PairTable& t;
  const int* cls;
  int row;  // class of site i times the number of classes
  template <bool kCohesive>
  PairBranch branch(int j, double r2) const {
    const int k = row + cls[j];
    const bool rep = !kCohesive || r2 <= t.rb2[k];
    const int b = 2 * k + (rep ? 0 : 1);
    return {t.rc2[k], t.tiny2[k], t.c[b], t.d[b], t.r0[b], t.e0[b]};
  }
};

// The constants of pair (i, j) computed from the diameters (fallback for many classes).
struct DirectPairs {
  const double* diam;
  const int* kind;
  const double* eps;  // the energies of site i's kind with kinds 0 and 1
  double alpha, beta, di;
  int ki;
  template <bool kCohesive>
  PairBranch branch(int j, double r2) const {
    const int kj = kind[j];
    const double cc = (ki | kj) == 0 ? 1.0 : 0.0;  // cohesion between cancer cells only
    const PairCoefficients c = pair_coefficients(0.5 * (di + diam[j]), eps[kj], alpha, cc * beta);
    const bool rep = !kCohesive || r2 <= c.rb2;
    return {c.rc2,
            c.tiny2,
            rep ? c.c_rep : c.c_att,
            rep ? c.d_rep : c.d_att,
            rep ? c.r0_rep : c.r0_att,
            rep ? c.e0 : 0.0};
  }
};

constexpr int kLanes = ContactRowScratch::kLanes;
using RowScratch = ContactRowScratch;

// Force, energy and virial of site i from its neighbour row nb[0..m). The pair terms are
// computed in a vectorisable loop into the scratch, then summed in row order (increasing
// index), so the sums do not depend on which sites beyond the cutoff the list holds (skin,
// build time) nor on the vector width.
template <bool kCohesive, bool kEnergy, bool kVirial, class Pairs>
void site_contacts(int i, const double* pos, const int* nb, int m, const MinimumImage& image,
                   const Pairs& pairs, RowScratch& b, Vec3& force, double& energy, Vec3& virial) {
  const double xi = pos[3 * i], yi = pos[3 * i + 1], zi = pos[3 * i + 2];
  // The minimum image with the box's constants in registers.
  const double hx = image.half(0), hy = image.half(1), hz = image.half(2);
  const double lx = image.length(0), ly = image.length(1), lz = image.length(2);
  auto wrap = [](double d, double half, double len) {
    return d > half ? d - len : (d < -half ? d + len : d);
  };
  double* __restrict gx = b.fx.data();
  double* __restrict gy = b.fy.data();
  double* __restrict gz = b.fz.data();
  double* __restrict ge = b.e.data();
  double* __restrict wx = b.wx.data();
  double* __restrict wy = b.wy.data();
  double* __restrict wz = b.wz.data();
  // The row padded to whole vectors with site i itself (masked out below), so that every
  // entry is computed in vector lanes (rows are short: a remainder loop would dominate).
  const int m_pad = (m + kLanes - 1) / kLanes * kLanes;
  int* __restrict idx = b.idx.data();
  for (int k = 0; k < m; ++k) idx[k] = nb[k];
  for (int k = m; k < m_pad; ++k) idx[k] = i;
  for (int k0 = 0; k0 < m_pad; k0 += kLanes) {
#pragma omp simd
    for (int k = k0; k < k0 + kLanes; ++k) {
      const int j = idx[k];
      const double dx = wrap(xi - pos[3 * j], hx, lx), dy = wrap(yi - pos[3 * j + 1], hy, ly),
                   dz = wrap(zi - pos[3 * j + 2], hz, lz);
      const double r2 = dx * dx + dy * dy + dz * dz;
      const PairBranch c = pairs.template branch<kCohesive>(j, r2);
      const bool in = r2 < c.rc2 && j != i;
      const double cf = c.c, df = c.d;
      const double r = std::sqrt(r2);
      const double inv_r = 1.0 / r;
      // Coincident sites: the force at r along a fixed direction, opposite for the partners.
      const bool coincident = r2 <= c.tiny2;
      const double f_over_r = cf * inv_r - df;
      const double sign = i < j ? 1.0 : -1.0;
      const double fx = coincident ? (cf - df * r) * sign : f_over_r * dx;
      const double fy = coincident ? 0.0 : f_over_r * dy;
      const double fz = coincident ? 0.0 : f_over_r * dz;
      gx[k] = in ? fx : 0.0;
      gy[k] = in ? fy : 0.0;
      gz[k] = in ? fz : 0.0;
      if constexpr (kEnergy) {
        const double u = 0.5 * df * (r - c.r0) * (r - c.r0) + c.e0;
        ge[k] = in ? 0.5 * u : 0.0;
      }
      if constexpr (kVirial) {
        wx[k] = in ? 0.5 * fx * dx : 0.0;
        wy[k] = in ? 0.5 * fy * dy : 0.0;
        wz[k] = in ? 0.5 * fz * dz : 0.0;
      }
    }
  }
  double fx = 0.0, fy = 0.0, fz = 0.0;
  for (int k = 0; k < m; ++k) {
    fx += gx[k];
    fy += gy[k];
    fz += gz[k];
  }
  force += Vec3(fx, fy, fz);
  if constexpr (kEnergy) {
    double e = 0.0;
    for (int k = 0; k < m; ++k) e += ge[k];
    energy = e;
  }
  if constexpr (kVirial) {
    double ax = 0.0, ay = 0.0, az = 0.0;
    for (int k = 0; k < m; ++k) {
      ax += wx[k];
      ay += wy[k];
      az += wz[k];
    }
    virial = Vec3(ax, ay, az);
  }
}

}  // namespace

void ContactRowScratch::reserve(std::size_t m) {
  m = (m + kLanes - 1) / kLanes * kLanes;
  if (idx.size() < m) idx.resize(m);
  for (auto* v : {&fx, &fy, &fz, &e, &wx, &wy, &wz})
    if (v->size() < m) v->resize(m);
}

// The kernel's rows shared by the team (orphaned `omp for`; its end is the barrier after which
// every force is added).
template <bool kCohesive, bool kEnergy, bool kVirial>
void ContactForce::add_forces_impl(System& sys, ContactRowScratch& scratch) {
  Sites& s = sys.sites();
  const std::size_t n = s.size();
  const MinimumImage image(sys.box());
  static_assert(sizeof(Vec3) == 3 * sizeof(double), "positions are read as a flat array");
  const double* pos = s.pos.data()->data();
  const double eps[2][2] = {{params_.eps_cc, params_.eps_cv}, {params_.eps_cv, params_.eps_vv}};
#pragma omp for schedule(dynamic, 128)
  for (std::size_t i = 0; i < n; ++i) {
    double e = 0.0;
    Vec3 w = Vec3::Zero();
    const int* nb = list_.neighbors(i);
    const int m = list_.count(i);
    if (table_.usable()) {
      const TablePairs pairs{table_, table_.site_class(),
                             table_.site_class()[i] * table_.n_classes()};
      site_contacts<kCohesive, kEnergy, kVirial>(int(i), pos, nb, m, image, pairs, scratch,
                                                 s.force[i], e, w);
    } else {
      const DirectPairs pairs{s.diameter.data(), table_.site_kind(), eps[int(s.kind[i])],
                              params_.alpha,     params_.beta,       s.diameter[i],
                              int(s.kind[i])};
      site_contacts<kCohesive, kEnergy, kVirial>(int(i), pos, nb, m, image, pairs, scratch,
                                                 s.force[i], e, w);
    }
    if constexpr (kEnergy) site_energy_[i] = e;
    if constexpr (kVirial) site_virial_[i] = w;
  }
}

ForceResult ContactForce::add_forces(System& sys, const ForceFlags& flags) {
  return add_forces_in_own_region(sys, flags);
}

bool ContactForce::prepare_team(System& sys, const ForceFlags& flags) {
  list_.prepare_update(sys);  // throws for a periodic box too short for the cutoffs
  const std::size_t n = sys.n_sites();
  if (list_.rebuild_forced() || table_.n_sites() != n) table_.build(sys.sites(), params_);
  if (flags.energy) site_energy_.resize(n);
  if (flags.virial) site_virial_.resize(n);
  scratch_.resize(std::size_t(std::max(omp_get_max_threads(), 1)));
  return true;
}

ForceResult ContactForce::add_forces_team(System& sys, const ForceFlags& flags) {
  list_.update_team(sys);  // (ends with a barrier: the rows are complete)
  ContactRowScratch& scratch = scratch_[omp_get_thread_num()];
  scratch.reserve(list_.max_count());
  // One instantiation of the kernel per combination of the flags.
  const bool cohesive = params_.beta > 0.0;
  const bool want_e = flags.energy, want_v = flags.virial;
  using Impl = void (ContactForce::*)(System&, ContactRowScratch&);
  static constexpr Impl impls[8] = {&ContactForce::add_forces_impl<false, false, false>,
                                    &ContactForce::add_forces_impl<false, false, true>,
                                    &ContactForce::add_forces_impl<false, true, false>,
                                    &ContactForce::add_forces_impl<false, true, true>,
                                    &ContactForce::add_forces_impl<true, false, false>,
                                    &ContactForce::add_forces_impl<true, false, true>,
                                    &ContactForce::add_forces_impl<true, true, false>,
                                    &ContactForce::add_forces_impl<true, true, true>};
  (this->*impls[4 * cohesive + 2 * want_e + want_v])(sys, scratch);
  // The sums in index order on the leader (the same blocks as deterministic_sum).
  ForceResult out;
  if (!team_leader()) return out;
  const std::size_t n = sys.n_sites();
  if (want_e) out.energy = block_sum(n, 0.0, [&](std::size_t i) { return site_energy_[i]; });
  if (want_v)
    out.virial = block_sum(n, Vec3(Vec3::Zero()), [&](std::size_t i) { return site_virial_[i]; });
  return out;
}

}  // namespace invasim
