#pragma once
// The energy of every force term as an observation during a run: one extra evaluation with
// energies and virial, after which the site forces the Dynamics keeps between steps are put
// back, so the trajectory does not change.
#include <string>
#include <vector>

#include "forces/force.hpp"
#include "state/system.hpp"

namespace invasim {

struct EnergyTerms {
  ForceResult total;               // total energy and virial
  std::vector<std::string> names;  // per term: its name, a second term of a kind "contact2", ...
  std::vector<double> energies;    // per term, in the ForceField's order
};

// Evaluates the ForceField with energies and virial and restores the site forces. On an
// exception the site forces are left as the failed evaluation left them (the caller must
// invalidate its Dynamics).
EnergyTerms observe_energies(System& sys, ForceField& forces);

}  // namespace invasim
