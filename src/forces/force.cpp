#include "forces/force.hpp"

#include "core/errors.hpp"
#include "core/parallel.hpp"

namespace invasim {

bool Force::prepare_team(System&, const ForceFlags&) {
  return false;
}

ForceResult Force::add_forces_team(System&, const ForceFlags&) {
  // Unreachable: ForceField calls it only after prepare_team returned true.
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
    while (end < n_terms && terms_[end]->prepare_team(sys, flags)) ++end;
    return end;
  };
  // Terms [from, end) inside the current region; the hook `after` if they are the last.
  auto team_terms = [&](std::size_t from, std::size_t end) {
    for (std::size_t k = from; k < end; ++k) {
      const ForceResult r = terms_[k]->add_forces_team(sys, flags);
      if (team_leader()) results_[k] = r;
    }
    if (end == n_terms && hooks.after) hooks.after();
  };

  std::size_t k = team_run_end(0);
  // Zeroing alone is light work: a region of its own only for large systems.
  const bool more_in_first = k > 0 || (k == n_terms && hooks.after);
  const bool hook_zeroes = hooks.before && hooks.zeroes_forces;
  ++team_regions_;
#pragma omp parallel if (more_in_first || hooks.before ? parallel : parallel_light(f.size()))
  {
    if (hooks.before) {
      hooks.before();
      if (!hook_zeroes) {  // all reads of the old forces done before any is zeroed
#pragma omp barrier
      }
    }
    if (!hook_zeroes) {
#pragma omp for schedule(static) nowait
      for (std::size_t i = 0; i < f.size(); ++i) f[i].setZero();
    }
    if (more_in_first) {  // (otherwise the region's end is the barrier)
#pragma omp barrier
    }
    team_terms(0, k);
  }
  while (k < n_terms) {
    results_[k] = terms_[k]->add_forces(sys, flags);
    const std::size_t from = ++k;
    k = team_run_end(from);
    if (k == from && !(k == n_terms && hooks.after)) continue;
    ++team_regions_;
#pragma omp parallel if (parallel)
    team_terms(from, k);
  }

  ForceResult total;
  if (per_term) per_term->clear();
  for (const ForceResult& r : results_) {
    total.energy += r.energy;
    total.virial += r.virial;
    if (per_term) per_term->push_back(r);
  }
  return total;
}

}  // namespace invasim
