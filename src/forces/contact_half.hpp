#pragma once
// The contact kernel on one thread, each pair evaluated once (LAMMPS's half list, newton on),
// bit-identical to the full-row kernel of ContactForce (docs/performance.md, "Round 4:
// half-list kernel on one thread"). The full kernel sums site i's pair terms over its whole
// row in increasing index order. Here the rows are processed in increasing i, each computing
// only its suffix j > i (contact_kernel.hpp's stream_terms, the same bits as the full kernel's
// terms): the terms are added in row order to site i's accumulator and subtracted from site
// j's. Site j thus receives its terms from rows i < j in increasing i, all before its own row,
// then its own suffix in order: the same additions in the same order as the full row's sum
// (an accumulator that starts at +0 never holds -0, so minus (+0) and +0 terms add alike).
#include <vector>

#include "forces/contact_pairs.hpp"
#include "neighbor/verlet_list.hpp"

namespace invasim {

struct ContactParams;

// Adds the contact forces to sys's forces and, if requested, each site's half pair energies
// and virials to site_energy / site_virial (arrays of n_sites, zeroed by the caller). `sums`
// is the caller's scratch of per-site force accumulators (resized here). The table is the one
// built with the list (used when usable, else the constants from the diameters).
template <bool kCohesive, bool kEnergy, bool kVirial>
void contact_half_rows(System& sys, const VerletList& list, const PairTable& table,
                       const ContactParams& params, std::vector<Vec3>& sums, double* site_energy,
                       Vec3* site_virial);

}  // namespace invasim
