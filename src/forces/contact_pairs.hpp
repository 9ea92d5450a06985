#pragma once
// Constants of the contact law for one pair type, precomputed so that the contact kernel's
// inner loop needs no division by s: with F the force magnitude (positive = repulsive),
//   repulsive branch (r <= r_b):  F = eps/s (1 - r/s)  = c_rep - d_rep r,
//   attractive branch (r_b < r < r_a, cancer-cancer with cohesion): F = k (r - r_a)
//                                                     = c_att - d_att r,
// so the force vector is (c/r - d) (dx, dy, dz): one square root and one division per pair.
// The energy on each branch is U = d/2 (r - r0)^2 + e0. Sites are grouped in classes of equal
// (kind, diameter); PairTable holds the constants of every class pair (few classes in practice:
// the cancer-cell diameters and the vertex diameter).
#include <cstdint>
#include <vector>

#include "state/system.hpp"

namespace invasim {

struct ContactParams;

struct PairCoefficients {
  double rc2;     // squared cutoff: s^2, or r_a^2 for a cohesive pair
  double rb2;     // squared end of the repulsive branch (= rc2 without cohesion)
  double c_rep;   // eps / s
  double d_rep;   // eps / s^2
  double c_att;   // -k r_a, k = eps beta / (s^2 (alpha - beta)) (= c_rep without cohesion)
  double d_att;   // -k (= d_rep without cohesion)
  double r0_rep;  // s
  double r0_att;  // r_a (= s without cohesion)
  double e0;      // energy offset of the repulsive branch: -eps alpha beta / 2 (0 without)
  double tiny2;   // (1e-12 s)^2: closer sites count as coincident
};

// Constants of a pair with contact distance s and energy eps; beta = 0: purely repulsive.
// Written without branches so that the kernel's fallback path (many classes) vectorises.
inline PairCoefficients pair_coefficients(double s, double eps, double alpha, double beta) {
  const bool cohesive = beta > 0.0;
  const double inv_s = 1.0 / s;
  const double ra = (1.0 + alpha) * s, rb = (1.0 + beta) * s;
  const double k = cohesive ? eps * inv_s * inv_s * beta / (alpha - beta) : 0.0;
  PairCoefficients c;
  c.c_rep = eps * inv_s;
  c.d_rep = eps * inv_s * inv_s;
  c.r0_rep = s;
  c.rc2 = cohesive ? ra * ra : s * s;
  c.rb2 = cohesive ? rb * rb : s * s;
  c.c_att = cohesive ? -k * ra : c.c_rep;
  c.d_att = cohesive ? -k : c.d_rep;
  c.r0_att = cohesive ? ra : s;
  c.e0 = cohesive ? -0.5 * eps * alpha * beta : 0.0;
  c.tiny2 = (1e-12 * s) * (1e-12 * s);
  return c;
}

// The pair type's constants for sites of kinds ka, kb and diameters da, db (cohesion between
// two cancer cells, adhesion between a cancer cell and a vertex: ContactParams::pair_beta).
PairCoefficients pair_coefficients(const ContactParams& p, SiteKind ka, SiteKind kb, double da,
                                   double db);

// Classes of sites with equal (kind, diameter) and the constants of every class pair, stored
// field by field (structure of arrays, entry t = ci * n_classes + cj, both branches' constants
// in their own arrays), zero-padded to at least kLookupEntries entries: the kernel looks a
// batch's constants up ahead of its pair loop (contact_kernel.hpp, look_up_pairs), from
// registers with vector permutes when the table has at most kLookupEntries class pairs.
class PairTable {
 public:
  static constexpr int kMaxClasses = 16;
  static constexpr int kLookupEntries = 16;  // class pairs one two-register permute can index
  // Assigns the classes and fills the table; false (table unusable) when the sites have more
  // than kMaxClasses distinct (kind, diameter).
  bool build(const Sites& s, const ContactParams& p);
  bool usable() const { return usable_; }
  // Distinct for every build of every table (a plan made with one build is stale for another).
  std::uint64_t version() const { return version_; }
  int n_classes() const { return n_classes_; }
  // Sites of the last build.
  std::size_t n_sites() const { return cls_.size(); }
  const int* site_class() const { return cls_.data(); }
  // The table entry of the pair of sites i and j: ci * n_classes + cj.
  int class_pair(std::size_t i, std::size_t j) const { return cls_[i] * n_classes_ + cls_[j]; }
  // The sites' kinds as ints (for the gathers of the fallback path without a table).
  const int* site_kind() const { return kind_.data(); }

  std::vector<double> rc2, rb2, tiny2;       // per class pair
  std::vector<double> c_rep, d_rep, r0_rep;  // the repulsive branch's constants
  std::vector<double> c_att, d_att, r0_att;  // the attractive branch's (e0 is 0 there)
  std::vector<double> e0;                    // the repulsive branch's energy offset

 private:
  bool usable_ = false;
  int n_classes_ = 0;
  std::uint64_t version_ = 0;
  std::vector<int> cls_, kind_;
};

}  // namespace invasim
