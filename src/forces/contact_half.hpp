#pragma once
// The contact kernel with each pair evaluated once (LAMMPS's half list, newton on), on any
// number of threads, bit-identical to the full-row kernel of ContactForce
// (docs/performance.md, "Half rows").
//
// The full kernel sums site i's pair terms over its whole row in increasing index order. The
// half rows give every site the same additions in the same order: rows are processed in
// increasing i, each computing only its suffix j > i (contact_kernel.hpp's stream_terms, the
// same bits as the full kernel's terms); a row's terms are added in order to site i's
// accumulator and subtracted from site j's. Site j thus receives its terms from rows i < j in
// increasing i, all before its own row, then its own suffix in order (an accumulator that
// starts at +0 never holds -0, so minus (+0) and +0 terms add alike).
//
// Several threads: every site is owned by one thread (partition_sites: slabs along one axis,
// so that few pairs cross between threads). A thread accumulates its own sites' terms in an
// array of its own (indexed by the site's rank among them: no cache line is written by two
// threads) and writes each site's force once. It processes, in increasing index, its own rows
// (their whole suffix; the terms of partners it does not own go to a spare slot) and the halo
// rows: rows of other threads' sites i that have a partner j > i it owns, restricted to those
// partners. So each of its sites receives exactly the sequence above, and a pair across
// threads is computed by both (the same bits). The results depend neither on the partition
// nor on the number of threads.
#include <vector>

#include "forces/contact_kernel.hpp"
#include "forces/contact_pairs.hpp"
#include "neighbor/verlet_list.hpp"

namespace invasim {

struct ContactParams;

// One thread's rows of the half kernel, from the neighbour list and the owner of each site,
// and the thread's accumulators (its sites in increasing index, then the spare slot).
struct HalfRowsPlan {
  std::vector<int> rows;             // sites whose rows the thread processes, increasing
  std::vector<unsigned char> owned;  // per row: the thread owns its site (else a halo row)
  std::vector<int> start;            // row r's entries: [start[r], start[r + 1])
  std::vector<int> partner;          // each entry's site j > i
  std::vector<int> target;           // the accumulator of j if owned, else the spare
  std::size_t n_owned = 0;           // the thread's sites (the spare slot is n_owned)
  std::vector<Vec3> sums;            // force accumulators (kernel's work space)
  std::vector<double> energy;        // half pair energies
  std::vector<Vec3> virial;          // half pair virials
  std::vector<unsigned char> halo;   // plan_half_rows' scratch (all zero between calls)
  // Each entry's class pair, filled by contact_half_rows from the PairTable whose version is
  // pair_class_table (0: none yet; plan_half_rows resets it).
  std::vector<int> pair_class;
  std::uint64_t pair_class_table = 0;
};

// The axis along which partition_sites cuts `parts` slabs: the one whose cuts cross the least
// area (positions are wrapped on periodic axes).
int slab_axis(const System& sys, int parts);

// The owner (0 .. parts-1) of every site: slabs along the axis whose cuts cross the least
// area (positions are wrapped on periodic axes), balanced by the sites' row lengths.
void partition_sites(const System& sys, const VerletList& list, int parts, std::vector<int>& owner);

// Plans thread `thread`'s rows for any owner assignment. `rank` is scratch of n_sites entries
// shared by the team (each thread writes its own sites' ranks).
void plan_half_rows(const VerletList& list, const std::vector<int>& owner, int thread,
                    std::vector<int>& rank, HalfRowsPlan& plan);

// Adds the contact forces of the plan's sites to sys's forces and, if requested, their half
// pair energies and virials to site_energy / site_virial (arrays of n_sites: the plan's sites
// are written). The table is the one built with the list (used when usable, else the
// constants from the diameters). `scratch` is the thread's own.
template <bool kCohesive, bool kEnergy, bool kVirial>
void contact_half_rows(System& sys, HalfRowsPlan& plan, std::size_t max_count,
                       const PairTable& table, const ContactParams& params, double* site_energy,
                       Vec3* site_virial, contact_detail::RowScratch& scratch);

}  // namespace invasim
