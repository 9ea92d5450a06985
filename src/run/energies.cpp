#include "run/energies.hpp"

#include <algorithm>

namespace invasim {

EnergyTerms observe_energies(System& sys, ForceField& forces) {
  std::vector<ForceResult> per_term;
  std::vector<Vec3> saved = sys.sites().force;
  EnergyTerms out;
  out.total = forces.compute(sys, {true, true}, &per_term);
  sys.sites().force.swap(saved);
  const auto& terms = forces.terms();
  for (std::size_t k = 0; k < terms.size(); ++k) {
    std::string key = terms[k]->name();
    for (int n = 2; std::find(out.names.begin(), out.names.end(), key) != out.names.end(); ++n)
      key = terms[k]->name() + std::to_string(n);
    out.names.push_back(key);
    out.energies.push_back(per_term[k].energy);
  }
  return out;
}

}  // namespace invasim
