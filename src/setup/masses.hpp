#pragma once
// Site masses after construction: a protocol gives the adipocyte vertices a mass other than the
// cells' (docs/model.md, "Vertex bath": the vertex mass is one of the readings of the paper's
// vertex equation, which names a mass without a value). The velocities are kept, so the
// kinetic energy scales with the mass; protocols set masses before the dynamics starts.
#include <vector>

#include "state/system.hpp"

namespace invasim {

// Sets the mass of `sites` to `mass` (InputError for a mass that is not finite and > 0 or a
// site outside the System).
void set_masses(System& sys, const std::vector<int>& sites, double mass);

}  // namespace invasim
