#pragma once
// The force interface: a force term reads the state and adds its forces into
// sites().force, and, when asked, returns its potential energy and virial. Integrators and
// the minimiser see forces only through a ForceField (a list of terms), so adding a term
// touches no integrator.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "state/system.hpp"

namespace invasim {

struct ForceFlags {
  bool energy = false;
  bool virial = false;
};

// Energy and the diagonal of the virial W_aa = sum over interactions of r_a F_a (so that
// W_aa = -dU/d(ln L_a) under an affine stretch of axis a).
struct ForceResult {
  double energy = 0.0;
  Vec3 virial = Vec3::Zero();
};

class Force {
 public:
  virtual ~Force() = default;
  virtual std::string name() const = 0;
  // Adds this term's forces into sys.sites().force.
  virtual ForceResult add_forces(System& sys, const ForceFlags& flags) = 0;
  // Drops cached state derived from positions (neighbour lists), e.g. after the System was
  // replaced by a checkpoint.
  virtual void invalidate_caches() {}

  // Team evaluation: a term can be evaluated inside a parallel region that ForceField::compute
  // shares with other terms and the integrator (one region per step instead of one per loop;
  // every term of the full system supports it, the contacts with their list update).
  // supports_team() says whether the term does (fixed for the term, so that Dynamics can know it
  // before a step's serial part and keep one region over many steps). prepare_team runs on one
  // thread before the region (validates, throws on bad input, sizes scratch); then every thread
  // of the region calls add_forces_team, which shares its loops with orphaned `omp for`, must not
  // throw and ends with a barrier (all its forces added); the team leader's return value is the
  // term's result. Default: not supported (add_forces runs between regions).
  virtual bool supports_team() const { return false; }
  virtual void prepare_team(System&, const ForceFlags&) {}
  virtual ForceResult add_forces_team(System& sys, const ForceFlags& flags);
  // The thread that owns each site (by storage slot) in the term's team evaluation, where the
  // term partitions the sites among the threads (the contact kernel's slabs), else nullptr;
  // `version` changes with each new partition and `parts` is its number of threads. Other
  // per-site loops of a step follow it, so that a site's data stays in one core's cache. Read
  // only between the term's evaluations (it changes inside them).
  virtual const std::vector<int>* site_owner(std::uint64_t& /*version*/, int& /*parts*/) const {
    return nullptr;
  }

 protected:
  // add_forces of a team-capable term: prepare_team, then add_forces_team in a region of its own.
  ForceResult add_forces_in_own_region(System& sys, const ForceFlags& flags);
};

// A term evaluated by a team (every term of the model is): add_forces runs prepare_team and
// add_forces_team in a parallel region of its own.
class TeamForce : public Force {
 public:
  ForceResult add_forces(System& sys, const ForceFlags& flags) final {
    return add_forces_in_own_region(sys, flags);
  }
  bool supports_team() const final { return true; }
  void prepare_team(System& sys, const ForceFlags& flags) override = 0;
  ForceResult add_forces_team(System& sys, const ForceFlags& flags) override = 0;
};

// Work of the integrator done by every thread of ForceField::compute's parallel regions (its
// loops shared with orphaned `omp for`, no exceptions; ForceField adds the barriers around
// them). `before` runs in the first region before the forces are zeroed; if `zeroes_forces`,
// it zeroes every site's force itself (each after its last read) and ForceField does not.
// `after` runs after the last term has added its forces (in the last term's region when that
// term supports team evaluation).
struct TeamHooks {
  std::function<void()> before, after;
  bool zeroes_forces = false;
};

// An ordered list of force terms, evaluated together.
class ForceField {
 public:
  void add(std::shared_ptr<Force> force) { terms_.push_back(std::move(force)); }
  const std::vector<std::shared_ptr<Force>>& terms() const { return terms_; }
  // Zeroes all site forces, then adds every term; result per term in `per_term` if given.
  // Consecutive team-capable terms share one parallel region, together with the zeroing (if
  // they lead) and the hooks; every other term runs on its own between them. The forces on
  // each site are summed in term order whatever the grouping and the thread count.
  ForceResult compute(System& sys, const ForceFlags& flags = {},
                      std::vector<ForceResult>* per_term = nullptr, const TeamHooks& hooks = {});
  // compute() split for a caller that keeps one parallel region over many time steps
  // (Dynamics::run, docs/performance.md "Team steps and the barrier"); only if supports_team(). The
  // team's leader calls prepare_team_step (it may throw; the other threads wait at a barrier after
  // it), then every thread of the team calls compute_team, which ends with the hook `after` (no
  // barrier after it); team_result() then gives the leader the total, as compute returns it.
  bool supports_team() const;
  // The first term's site partition (Force::site_owner), or nullptr.
  const std::vector<int>* site_owner(std::uint64_t& version, int& parts) const;
  void prepare_team_step(System& sys, const ForceFlags& flags);
  void compute_team(System& sys, const ForceFlags& flags, const TeamHooks& hooks);
  ForceResult team_result() const;
  // Total potential energy (forces are recomputed as a side effect).
  double energy(System& sys) { return compute(sys, {true, false}).energy; }
  // Parallel regions opened by the last compute (for tests and benchmarks; regions opened by
  // the terms' own add_forces are not counted).
  int team_regions() const { return team_regions_; }

 private:
  std::vector<std::shared_ptr<Force>> terms_;
  std::vector<ForceResult> results_;
  int team_regions_ = 0;
  // The body of compute's first region: the hook `before`, the zeroing, then terms [0, end)
  // (and `after` if end is the last term).
  void first_region(System& sys, const ForceFlags& flags, const TeamHooks& hooks, std::size_t end);
  // Terms [from, end) inside the current region (every thread); the hook `after` if they are the
  // last.
  void team_terms(System& sys, const ForceFlags& flags, const TeamHooks& hooks, std::size_t from,
                  std::size_t end);
};

}  // namespace invasim
