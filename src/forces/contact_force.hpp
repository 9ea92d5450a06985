#pragma once
// Linear-spring contacts between all sites (docs/model.md, "Forces"):
//   vertex-vertex of different adipocytes and vertex-cancer: F = (eps/s)(1 - r/s) for r <= s;
//   cancer-cancer: the same repulsion plus cohesion, attractive from s to r_b = (1+beta)s and
//   falling linearly to zero at r_a = (1+alpha)s.
//   cancer-vertex: optionally the same form with its own (alpha_cv, beta_cv): the adhesion of
//   cancer cells to adipocytes, which the paper leaves purely repulsive (beta_cv = 0, the
//   default; docs/model.md, Forces, "Cancer-adipocyte adhesion").
// s is the mean of the two diameters. One pass over one neighbour list serves all kinds.
#include "forces/contact_half.hpp"
#include "forces/contact_kernel.hpp"
#include "forces/contact_pairs.hpp"
#include "forces/force.hpp"
#include "neighbor/verlet_list.hpp"

namespace invasim {

// The fields' meanings, units and ranges are declared once, with their Lua keys, in
// src/lua/bind_contacts.cpp (`invasim keys Contacts`); the values here are their defaults.
struct ContactParams {
  double eps_cc = 1.0, eps_cv = 1.0, eps_vv = 1.0;  // contact energies by pair kind
  double alpha = 0.2, beta = 0.0;                   // cancer-cancer cohesion
  double alpha_cv = 0.2, beta_cv = 0.0;             // cancer-vertex adhesion
  double skin = 0.3;
  // Throws InputError naming the bad value.
  void validate() const;
  // Whether any pair kind attracts (the kernel's cohesive branch is needed).
  bool attractive() const { return beta > 0.0 || beta_cv > 0.0; }
  // The (alpha, beta) of a pair of kinds: cancer-cancer (alpha, beta), cancer-vertex
  // (alpha_cv, beta_cv) or vertex-vertex (beta 0: alpha is not used).
  double pair_alpha(bool cancer_vertex) const { return cancer_vertex ? alpha_cv : alpha; }
  double pair_beta(bool cancer_cancer, bool cancer_vertex) const {
    return cancer_cancer ? beta : (cancer_vertex ? beta_cv : 0.0);
  }
};

// Pair force magnitude along r_hat (positive = repulsive) and pair energy, for separation r,
// contact distance s, energy eps and cohesion (alpha, beta). Exposed for tests.
struct PairEval {
  double force;
  double energy;
};
PairEval linear_spring(double r, double s, double eps);
PairEval cohesive_spring(double r, double s, double eps, double alpha, double beta);

// Which driver of the contact kernel runs: the half rows (each pair once, on any number of
// threads, contact_half.hpp; the default) or the full rows (each pair twice, for tests and
// benchmarks). Results are bit-identical either way.
enum class ContactKernel { kHalfRows, kFullRows };

// Team-capable (Force::prepare_team): inside the time step's one parallel region, the
// neighbour list's rebuild test and build (VerletList::update_team), then the kernel: each
// thread its half rows (re-planned after every list build and when the team's size changes),
// or the full rows as an orphaned `omp for`. The class table is rebuilt in prepare_team when
// the list's rebuild is forced (sites added, checkpoint loaded, new parameters: the only
// changes of kinds and diameters). add_forces runs the same code in a region of its own.
class ContactForce : public TeamForce {
 public:
  explicit ContactForce(const ContactParams& params);
  std::string name() const override { return "contact"; }
  void prepare_team(System& sys, const ForceFlags& flags) override;
  ForceResult add_forces_team(System& sys, const ForceFlags& flags) override;
  const ContactParams& params() const { return params_; }
  // Changes the parameters (e.g. cohesion switched on after compression); the neighbour
  // list is rebuilt with the new cutoffs and skin at the next evaluation.
  void set_params(const ContactParams& params);
  void invalidate_caches() override { list_.invalidate(); }
  VerletList& neighbor_list() { return list_; }
  void set_kernel(ContactKernel kernel) { kernel_ = kernel; }
  // The half-row kernel's slabs (partition_sites), once it has made one.
  const std::vector<int>* site_owner(std::uint64_t& version, int& parts) const override {
    if (kernel_ != ContactKernel::kHalfRows || partitions_ == 0) return nullptr;
    version = partitions_;
    parts = plan_threads_;
    return &owner_;
  }

 private:
  // The kernel, specialised for cohesion and for the requested energy and virial.
  template <bool kCohesive, bool kEnergy, bool kVirial>
  void add_forces_impl(System& sys, contact_detail::RowScratch& scratch);
  ContactParams params_;
  VerletList list_;
  PairTable table_;  // rebuilt with the list (sites added, checkpoint loaded, new parameters)
  std::vector<double> site_energy_;
  std::vector<Vec3> site_virial_;
  std::vector<contact_detail::RowScratch> scratch_;  // one per thread, sized by prepare_team
  ContactKernel kernel_ = ContactKernel::kHalfRows;
  // The half-row driver: the owner and the rank among its owner's sites of each site, each
  // thread's plan, and the list build and team size the plans are for (planned_* as of
  // prepare_team: read in the region, never written there).
  std::vector<int> owner_, rank_;
  std::vector<HalfRowsPlan> plans_;
  std::uint64_t plan_builds_ = ~std::uint64_t(0), planned_builds_ = ~std::uint64_t(0);
  int plan_threads_ = 0, planned_threads_ = 0;
  std::uint64_t partitions_ = 0;  // partition_sites calls so far (site_owner's version)
};

}  // namespace invasim
