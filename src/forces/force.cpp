#include "forces/force.hpp"

#include "core/errors.hpp"
#include "core/parallel.hpp"
#include "core/team_barrier.hpp"

namespace invasim {

ForceResult Force::add_forces_team(System&, const ForceFlags&) {
  // Unreachable: ForceField calls it only for terms that support team evaluation.
  return {};
}

ForceResult Force::add_forces_in_own_region(System& sys, const ForceFlags& flags) {
  prepare_team(sys, flags);
  ForceResult out;
#pragma omp parallel if (parallel_team(sys.n_sites()))
  {
    const ForceResult r = add_forces_team(sys, flags);
    if (team_leader()) out = r;
  }
  return out;
}

void ForceField::first_region(System& sys, const ForceFlags& flags, const TeamHooks& hooks,
                              std::size_t end) {
  auto& f = sys.sites().force;
  const bool hook_zeroes = hooks.before && hooks.zeroes_forces;
  if (hooks.before) {
    hooks.before();
    if (!hook_zeroes) team_barrier();  // all reads of the old forces done before any is zeroed
  }
  if (!hook_zeroes) {
#pragma omp for schedule(static) nowait
    for (std::size_t i = 0; i < f.size(); ++i) f[i].setZero();
  }
  const bool more = end > 0 || (end == terms_.size() && hooks.after);
  if (more) team_barrier();  // (otherwise the region's end is the barrier)
  team_terms(sys, flags, hooks, 0, end);
}

void ForceField::team_terms(System& sys, const ForceFlags& flags, const TeamHooks& hooks,
                            std::size_t from, std::size_t end) {
  for (std::size_t k = from; k < end; ++k) {
    const ForceResult r = terms_[k]->add_forces_team(sys, flags);
    if (team_leader()) results_[k] = r;
  }
  if (end == terms_.size() && hooks.after) hooks.after();
}

bool ForceField::supports_team() const {
  for (const auto& t : terms_)
    if (!t->supports_team()) return false;
  return true;
}

const std::vector<int>* ForceField::site_owner(std::uint64_t& version, int& parts) const {
  for (const auto& t : terms_)
    if (const std::vector<int>* owner = t->site_owner(version, parts)) return owner;
  return nullptr;
}

void ForceField::prepare_team_step(System& sys, const ForceFlags& flags) {
  results_.assign(terms_.size(), ForceResult{});
  for (const auto& t : terms_) t->prepare_team(sys, flags);
  team_regions_ = 1;  // (the caller's region)
}

void ForceField::compute_team(System& sys, const ForceFlags& flags, const TeamHooks& hooks) {
  first_region(sys, flags, hooks, terms_.size());
}

ForceResult ForceField::team_result() const {
  ForceResult total;
  for (const ForceResult& r : results_) {
    total.energy += r.energy;
    total.virial += r.virial;
  }
  return total;
}

ForceResult ForceField::compute(System& sys, const ForceFlags& flags,
                                std::vector<ForceResult>* per_term, const TeamHooks& hooks) {
  auto& f = sys.sites().force;
  const std::size_t n_terms = terms_.size();
  results_.assign(n_terms, ForceResult{});
  team_regions_ = 0;
  const bool parallel = parallel_team(f.size());
  // End of the run of team-capable terms starting at `from` (each prepared on this thread).
  auto team_run_end = [&](std::size_t from) {
    std::size_t end = from;
    for (; end < n_terms && terms_[end]->supports_team(); ++end)
      terms_[end]->prepare_team(sys, flags);
    return end;
  };

  std::size_t k = team_run_end(0);
  // Zeroing alone is light work: a region of its own only for large systems.
  const bool more_in_first = k > 0 || (k == n_terms && hooks.after);
  ++team_regions_;
#pragma omp parallel if (more_in_first || hooks.before ? parallel : parallel_light(f.size()))
  first_region(sys, flags, hooks, k);
  while (k < n_terms) {
    results_[k] = terms_[k]->add_forces(sys, flags);
    const std::size_t from = ++k;
    k = team_run_end(from);
    if (k == from && !(k == n_terms && hooks.after)) continue;
    ++team_regions_;
#pragma omp parallel if (parallel)
    team_terms(sys, flags, hooks, from, k);
  }

  if (per_term) per_term->assign(results_.begin(), results_.end());
  return team_result();
}

}  // namespace invasim
