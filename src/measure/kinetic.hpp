#pragma once
// Kinetic temperature of a set of sites (docs/measurements_dynamics.md, "Thermo columns"):
// equipartition kT = 1/(3N) sum_i m_i |v_i|^2.
#include <vector>

#include "state/system.hpp"

namespace invasim {

// kT of the sites; NaN for an empty list (no cells left, a tissue without adipocytes: the
// temperature is undefined, and a 0 would read as a frozen group). Indices must be valid sites.
double temperature(const System& sys, const std::vector<int>& sites);

}  // namespace invasim
