#pragma once
// Proliferation and death of cancer cells (docs/model.md, "Proliferation and death"), one of
// the paper's future directions ("Conclusions and future directions"). Applied every N steps
// (Simulation's ProliferationOperation) with elapsed = N dt: each cancer cell dies with
// probability 1 - exp(-death_rate elapsed), else divides with probability
// 1 - exp(-division_rate elapsed) unless contact inhibition holds it back (it touches at least
// `inhibition_contacts` sites: cells or adipocyte vertices closer than the contact distance
// (d_i + d_j)/2). A division moves the parent back by separation d/2 along a random axis and
// places a daughter of the same diameter, mass and orientation separation d/2 forward; the
// two share the parent's momentum (each gets half its velocity). Every draw is keyed by (seed,
// step, cell index, stream kProliferation), and the changes are made in index order, serially:
// the result does not depend on the thread count.
#include <utility>
#include <vector>

#include "state/system.hpp"

namespace invasim {

struct ProliferationParams {
  double division_rate = 0.0;   // 1/tau_div: divisions per cell per unit time
  double death_rate = 0.0;      // deaths per cell per unit time
  int inhibition_contacts = 0;  // a cell with at least this many contacts does not divide (0: off)
  double separation = 0.1;      // daughters' centre distance, as a fraction of the diameter
  void validate() const;        // throws InputError naming the bad value
};

// What one application changed: the new index of every site that existed before (-1: died)
// and, for each cell born, its index and its parent's (both new indices).
struct SiteChange {
  std::vector<int> new_index;
  std::vector<std::pair<int, int>> born;  // (daughter, parent)
  int deaths = 0;
  bool empty() const { return born.empty() && deaths == 0; }
  // Maps a list of old indices to new ones, dropping the removed sites and adding, after each
  // parent in the list, its daughters (a group follows its cells through their divisions).
  std::vector<int> follow(const std::vector<int>& old_sites) const;
};

class Proliferation {
 public:
  explicit Proliferation(const ProliferationParams& params);
  const ProliferationParams& params() const { return params_; }
  // Divisions and deaths for `elapsed` time at the System's current step (user layout).
  SiteChange apply(System& sys, double elapsed) const;
  // For every cancer cell (in index order), the sites it touches now.
  std::vector<int> contacts(const System& sys) const;

 private:
  ProliferationParams params_;
};

}  // namespace invasim
