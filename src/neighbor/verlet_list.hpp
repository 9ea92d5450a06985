#pragma once
// Full Verlet neighbour list built from a cell list, with a skin. Each site lists every
// other site within its pair cutoff + skin (both directions, so forces are a per-site gather:
// no atomics, and a summation order that does not depend on the thread count), in increasing
// index order. Vertices of the same adipocyte are excluded. The list rebuilds itself only when
// some site has moved more than half the skin since the last build, the periodic box changed,
// or sites were added. The build sorts the sites by class (kind) and cell, with their data
// copied in that order, and scans for each site only the cells of its class pair's stencil
// (cell_stencil.hpp): contiguous runs of candidates, about the volume of the pair's reach.
// Each pair is tested once, from the site first in that order, and entered in both rows
// (the cutoff rule must be symmetric); then the rows are sorted.
#include <array>
#include <cstdint>
#include <vector>

#include "neighbor/cell_stencil.hpp"
#include "state/system.hpp"

namespace invasim {

// Cutoff of a pair = factor[kind_i][kind_j] * (d_i + d_j) / 2 (factor symmetric).
struct CutoffRule {
  std::array<std::array<double, 2>, 2> factor{{{1.0, 1.0}, {1.0, 1.0}}};
  double of(SiteKind a, SiteKind b, double da, double db) const {
    return factor[int(a)][int(b)] * 0.5 * (da + db);
  }
};

class VerletList {
 public:
  explicit VerletList(double skin = 0.3);

  void set_cutoff_rule(const CutoffRule& rule);
  double skin() const { return skin_; }
  // Rebuilds if needed; returns true when it rebuilt.
  bool update(const System& sys);
  // Forces a rebuild at the next update.
  void invalidate() { valid_ = false; }

  // Full row of site i (count(i) entries, increasing index).
  int count(std::size_t i) const { return counts_[i]; }
  const int* neighbors(std::size_t i) const { return &list_[i * stride_]; }
  std::uint64_t builds() const { return builds_; }
  // Longest row of the last build.
  std::size_t max_count() const { return max_count_; }
  // Candidate pairs tested by the last build (for tests and benchmarks).
  std::uint64_t candidates() const { return candidates_; }

  // Builds the list unconditionally.
  void build(const System& sys);

 private:
  bool needs_rebuild(const System& sys) const;
  double skin_;
  CutoffRule rule_;
  bool valid_ = false;
  std::uint64_t builds_ = 0;
  std::uint64_t box_version_ = 0;
  std::size_t stride_ = 64;
  std::size_t max_count_ = 0;
  std::uint64_t candidates_ = 0;
  std::vector<int> counts_, upper_;
  std::vector<int> list_;
  std::vector<Vec3> pos_at_build_;
  // Cell list scratch: the grid, the (class, cell) bin of each site, sites sorted by bin
  // (bin start offsets, class-major) and their data in that order.
  CellStencils grid_;
  std::vector<int> cell_of_, cell_start_, cell_sites_;
  std::vector<Vec3> cell_pos_;
  std::vector<double> cell_diam_;
  std::vector<int> cell_body_;
  std::vector<SiteKind> cell_kind_;
};

}  // namespace invasim
