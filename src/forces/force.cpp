#include "forces/force.hpp"
#include "core/parallel.hpp"

namespace invasim {

ForceResult ForceField::compute(System& sys, const ForceFlags& flags,
                                std::vector<ForceResult>* per_term) {
  auto& f = sys.sites().force;
#pragma omp parallel for schedule(static) if (parallel_light(f.size()))
  for (std::size_t i = 0; i < f.size(); ++i) f[i].setZero();
  ForceResult total;
  if (per_term) per_term->clear();
  for (const auto& term : terms_) {
    const ForceResult r = term->add_forces(sys, flags);
    total.energy += r.energy;
    total.virial += r.virial;
    if (per_term) per_term->push_back(r);
  }
  return total;
}

}  // namespace invasim
