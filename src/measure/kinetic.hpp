#pragma once
// Kinetic temperature of a set of sites (docs/measurements_dynamics.md, "Thermo columns"):
// equipartition kT = 1/(3N) sum_i m_i |v_i|^2.
#include <vector>

#include "state/system.hpp"

namespace invasim {

// kT of the sites (0 for an empty list). Indices must be valid sites of sys.
double temperature(const System& sys, const std::vector<int>& sites);

}  // namespace invasim
