#include "forces/contact_force.hpp"
#include "core/parallel.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>

#include "core/deterministic_sum.hpp"
#include "core/errors.hpp"
#include "core/team_barrier.hpp"
#include "forces/contact_half.hpp"
#include "forces/contact_kernel.hpp"

namespace invasim {

void ContactParams::validate() const {
  require_positive("eps_cc", eps_cc);
  require_positive("eps_cv", eps_cv);
  require_positive("eps_vv", eps_vv);
  require_non_negative("alpha", alpha);
  require_non_negative("beta", beta);
  require_non_negative("alpha_cv", alpha_cv);
  require_non_negative("beta_cv", beta_cv);
  require_non_negative("skin", skin);
  if (beta > 0.0 && !(beta < alpha))
    fail_input("cohesion: beta = ", beta, " must be smaller than alpha = ", alpha,
               " (attraction peaks at r_b = (1+beta)s inside the range r_a = (1+alpha)s)");
  if (beta_cv > 0.0 && !(beta_cv < alpha_cv))
    fail_input("adhesion: beta_cv = ", beta_cv, " must be smaller than alpha_cv = ", alpha_cv,
               " (attraction peaks at r_b = (1+beta_cv)s inside the range r_a = (1+alpha_cv)s)");
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
  plan_builds_ = ~std::uint64_t(0);  // (the new list counts its builds from 0 again)
  CutoffRule rule;
  rule.factor[0][0] = params_.beta > 0.0 ? 1.0 + params_.alpha : 1.0;
  rule.factor[0][1] = rule.factor[1][0] = params_.beta_cv > 0.0 ? 1.0 + params_.alpha_cv : 1.0;
  list_.set_cutoff_rule(rule);
}

namespace {

using contact_detail::DirectPairs;
using contact_detail::RowScratch;
using contact_detail::TablePairs;

// Force, energy and virial of site i from its full neighbour row nb[0..m). The pair terms
// (contact_kernel.hpp) are summed in row order (increasing index), so the sums do not depend
// on which sites beyond the cutoff the list holds (skin, build time) nor on the vector width.
template <bool kCohesive, bool kEnergy, bool kVirial, class Pairs>
void site_contacts(int i, const double* pos, const int* nb, int m, const MinimumImage& image,
                   const Pairs& pairs, RowScratch& b, Vec3& force, double& energy, Vec3& virial) {
  contact_detail::row_terms<kCohesive, kEnergy, kVirial>(i, pos, nb, m, image, pairs, b);
  const double* gx = b.fx.data();
  const double* gy = b.fy.data();
  const double* gz = b.fz.data();
  double fx = 0.0, fy = 0.0, fz = 0.0;
  for (int k = 0; k < m; ++k) {
    fx += gx[k];
    fy += gy[k];
    fz += gz[k];
  }
  force += Vec3(fx, fy, fz);
  if constexpr (kEnergy) {
    double e = 0.0;
    for (int k = 0; k < m; ++k) e += b.e[k];
    energy = e;
  }
  if constexpr (kVirial) {
    double ax = 0.0, ay = 0.0, az = 0.0;
    for (int k = 0; k < m; ++k) {
      ax += b.wx[k];
      ay += b.wy[k];
      az += b.wz[k];
    }
    virial = Vec3(ax, ay, az);
  }
}

}  // namespace

// The kernel on the team: each thread its half rows (contact_half.hpp), or the full rows as an
// orphaned `omp for`; either ends with the barrier after which every force is added.
template <bool kCohesive, bool kEnergy, bool kVirial>
void ContactForce::add_forces_impl(System& sys, RowScratch& scratch) {
  Sites& s = sys.sites();
  const std::size_t n = s.size();
  const MinimumImage image(sys.box());
  static_assert(sizeof(Vec3) == 3 * sizeof(double), "positions are read as a flat array");
  const double* pos = s.pos.data()->data();
  const double eps[2][2] = {{params_.eps_cc, params_.eps_cv}, {params_.eps_cv, params_.eps_vv}};
  if (kernel_ == ContactKernel::kHalfRows) {
    const int threads = omp_get_num_threads(), me = omp_get_thread_num();
    // Re-plan after a list build or a change of the team's size (all threads agree: both are
    // known to every thread, and planned_* are not written in the region).
    if (planned_builds_ != list_.builds() || planned_threads_ != threads) {
#pragma omp single nowait
      {
        partition_sites(sys, list_, threads, owner_);
        ++partitions_;
        if (plans_.size() < std::size_t(threads)) plans_.resize(std::size_t(threads));
        rank_.resize(n);
        plan_builds_ = list_.builds();
        plan_threads_ = threads;
      }
      team_barrier();
      plan_half_rows(list_, owner_, me, rank_, plans_[std::size_t(me)]);
    }
    contact_half_rows<kCohesive, kEnergy, kVirial>(sys, plans_[std::size_t(me)], list_.max_count(),
                                                   table_, params_, site_energy_.data(),
                                                   site_virial_.data(), scratch);
    team_barrier();
    return;
  }
#pragma omp for schedule(dynamic, 128) nowait
  for (std::size_t i = 0; i < n; ++i) {
    double e = 0.0;
    Vec3 w = Vec3::Zero();
    const int* nb = list_.neighbors(i);
    const int m = list_.count(i);
    if (table_.usable()) {
      const TablePairs pairs{table_, table_.site_class()[i] * table_.n_classes(),
                             contact_detail::LookedUp(scratch)};
      site_contacts<kCohesive, kEnergy, kVirial>(int(i), pos, nb, m, image, pairs, scratch,
                                                 s.force[i], e, w);
    } else {
      const DirectPairs pairs{s.diameter.data(), table_.site_kind(), eps[int(s.kind[i])],
                              params_.alpha,     params_.beta,       params_.alpha_cv,
                              params_.beta_cv,   s.diameter[i],      int(s.kind[i])};
      site_contacts<kCohesive, kEnergy, kVirial>(int(i), pos, nb, m, image, pairs, scratch,
                                                 s.force[i], e, w);
    }
    if constexpr (kEnergy) site_energy_[i] = e;
    if constexpr (kVirial) site_virial_[i] = w;
  }
  team_barrier();
}

namespace {

// Contacts between the vertices of one body are excluded, and with them those between a body
// and its own periodic images: a body whose vertex spheres reach across a periodic axis would
// overlap its image with no force at all (one adipocyte of outer diameter 6 compressed into
// L = 5.1). Checked at every rebuild of the list from scratch: the first evaluation, a new box
// (compression, rescale) and a new storage layout (the engine order, chosen again every
// Dynamics::sort_every steps).
void require_bodies_clear_of_their_images(const System& sys) {
  const Box& box = sys.box();
  const Sites& s = sys.sites();
  for (std::size_t b = 0; b < sys.bodies().size(); ++b) {
    const int nv = sys.bodies()[b].n_vertices();
    Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
    double d_max = 0.0;
    for (int v = 0; v < nv; ++v) {
      const int slot = sys.body_slot(int(b), v);
      const Vec3 u = sys.unwrapped(std::size_t(slot));
      lo = lo.cwiseMin(u);
      hi = hi.cwiseMax(u);
      d_max = std::max(d_max, s.diameter[std::size_t(slot)]);
    }
    for (int a = 0; a < 3; ++a)
      if (box.periodic(a) && hi[a] - lo[a] + d_max > box.length(a))
        fail_input("adipocyte ", b, " spans ", hi[a] - lo[a], " + its vertex diameter ", d_max,
                   " along ", "xyz"[a], ", more than the periodic box length ", box.length(a),
                   ": it would overlap its own periodic image, and the vertices of one body do "
                   "not interact; enlarge the box");
  }
}

}  // namespace

void ContactForce::prepare_team(System& sys, const ForceFlags& flags) {
  list_.prepare_update(sys);  // throws for a periodic box too short for the cutoffs
  if (list_.rebuild_forced()) require_bodies_clear_of_their_images(sys);
  const std::size_t n = sys.n_sites();
  if (list_.rebuild_forced() || table_.n_sites() != n) table_.build(sys.sites(), params_);
  if (flags.energy) site_energy_.resize(n);
  if (flags.virial) site_virial_.resize(n);
  grow_to_team(scratch_);
  planned_builds_ = plan_builds_;
  planned_threads_ = plan_threads_;
}

ForceResult ContactForce::add_forces_team(System& sys, const ForceFlags& flags) {
  list_.update_team(sys);  // (ends with a barrier: the rows are complete)
  RowScratch& scratch = scratch_[omp_get_thread_num()];
  scratch.reserve(list_.max_count());
  // One instantiation of the kernel per combination of the flags.
  const bool cohesive = params_.attractive();
  const bool want_e = flags.energy, want_v = flags.virial;
  using Impl = void (ContactForce::*)(System&, RowScratch&);
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
