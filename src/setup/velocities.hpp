#pragma once
// Maxwell-Boltzmann velocities: each component of v_i is Gaussian with variance kT / m_i, so
// that <m v^2> = 3 kT. The numbers come from the counter-based RNG (stream kVelocity, keyed by
// the seed, the current step and the site), so they do not depend on the thread count or on
// which other sites are drawn.
#include <vector>

#include "state/system.hpp"

namespace invasim {

// Sets the velocities of `sites` (InputError naming a site outside the System).
void set_maxwell_boltzmann(System& sys, const std::vector<int>& sites, double kT);

}  // namespace invasim
