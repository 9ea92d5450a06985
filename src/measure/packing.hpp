#pragma once
// Packing fractions (docs/model.md, protocol step 2): phi_c = (pi/6) sum sigma_q^3 / V_box,
// phi_a = sum V_i / V_box with V_i the union volume of adipocyte i (mesh + vertex spheres,
// MeshBody::outer_volume), phi = phi_c + phi_a. V_box spans the walls in x.
#include "state/system.hpp"

namespace invasim {

struct PackingFractions {
  double total = 0.0;
  double cancer = 0.0;
  double adipocyte = 0.0;
};

PackingFractions packing_fractions(const System& sys);

}  // namespace invasim
