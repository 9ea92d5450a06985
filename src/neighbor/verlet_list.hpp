#pragma once
// Full Verlet neighbour list built from a cell list, with a skin. Each site lists every
// other site within its pair cutoff + skin (both directions, so forces are a per-site gather:
// no atomics, and a summation order that does not depend on the thread count), in increasing
// index order. Vertices of the same adipocyte are excluded. The list rebuilds itself only when
// some site has moved more than half the skin since the last build, the periodic box changed,
// sites were added or their storage layout changed (System::layout_id: rows hold storage slots).
// The build sorts the sites by class (kind) and cell, with their data copied in that order, and
// scans for each site only the cells of its class pair's stencil (cell_stencil.hpp): contiguous
// runs of candidates, about the volume of the pair's reach. Each pair is tested once, from the site
// first in that order, and entered in both rows (the cutoff rule must be symmetric; each thread
// mirrors its own rows' entries, placing them with an atomic per-row counter); then the rows are
// sorted, so the rows do not depend on the thread count. The test and the build can run inside a
// caller's parallel region (prepare_update / update_team).
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
  // Rebuilds if needed (in a parallel region of its own); returns true when it rebuilt.
  bool update(const System& sys);
  // Forces a rebuild at the next update.
  void invalidate() { valid_ = false; }

  // Team form of update, for a caller that shares one parallel region per time step
  // (ContactForce::add_forces_team). prepare_update runs on one thread before the region: it
  // decides whether a rebuild is forced (first build, sites added, box changed, invalidated)
  // and then sets up the grid and checks the box (throws InputError). Then every thread of the
  // region calls update_team: the rebuild test (each thread tests all sites, so all agree
  // without a barrier; skipped when forced) and, if due, the build (orphaned `omp for` / `omp
  // single` passes); it returns on every thread whether it rebuilt, must not throw, and ends with a
  // barrier (rows complete).
  void prepare_update(const System& sys);
  bool update_team(const System& sys);
  // True between a prepare_update that forced a rebuild and the end of that build.
  bool rebuild_forced() const { return forced_; }

  // Full row of site i (count(i) entries, increasing index).
  int count(std::size_t i) const { return counts_[i]; }
  const int* neighbors(std::size_t i) const { return &list_[i * stride_]; }
  std::uint64_t builds() const { return builds_; }
  // Longest row of the last build.
  std::size_t max_count() const { return max_count_; }
  // Row capacity: grows when a build's rows overflow it (for tests).
  std::size_t stride() const { return stride_; }
  // Candidate pairs tested by the last build (for tests and benchmarks).
  std::uint64_t candidates() const { return candidates_; }

  // Builds the list unconditionally (in a parallel region of its own).
  void build(const System& sys);

 private:
  // The classes' reach from the sites' kinds and diameters, the periodic-box check and the
  // cell grid (serial; throws InputError for a box too short).
  void setup_grid(const System& sys);
  // Team parts: the rebuild test (some site moved more than skin/2), the build.
  bool moved_team(const System& sys) const;
  void build_team(const System& sys);
  // Counting sort of the sites by (class, cell) and their data in that order (serial).
  void bin_sites(const Sites& s);
  // Per-thread results of a team pass, read by every thread after the pass's barrier (so all
  // take the same branch); one cache line each.
  struct alignas(64) ThreadSlot {
    int max_upper = 0, max_count = 0;
    std::uint64_t candidates = 0;
  };
  double skin_;
  CutoffRule rule_;
  bool valid_ = false;
  bool forced_ = false;
  std::uint64_t builds_ = 0;
  std::uint64_t box_version_ = 0;
  std::uint64_t layout_id_ = 0;
  std::size_t stride_ = 64;
  std::size_t max_count_ = 0;
  std::uint64_t candidates_ = 0;
  std::vector<int> counts_, upper_;
  std::vector<int> list_;
  std::vector<Vec3> pos_at_build_;
  std::vector<ThreadSlot> slots_;
  // Cell list scratch: the grid, the (class, cell) bin of each site, sites sorted by bin
  // (bin start offsets, class-major) and their data in that order.
  static constexpr int kClasses = 2;  // the site kinds
  CellStencils grid_;
  std::vector<int> cell_of_, cell_start_, cell_sites_;
  std::vector<double> cell_x_, cell_y_, cell_z_;
  std::vector<double> cell_diam_;
  std::vector<int> cell_body_;
};

}  // namespace invasim
