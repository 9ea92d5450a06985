#include "neighbor/verlet_list.hpp"
#include "core/parallel.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"

namespace invasim {

VerletList::VerletList(double skin) : skin_(skin) {
  if (!(skin >= 0.0)) fail_input("neighbour list: skin = ", skin, " must be >= 0");
}

void VerletList::set_cutoff_rule(const CutoffRule& rule) {
  if (rule.factor[0][1] != rule.factor[1][0])
    fail_input("neighbour list: cutoff factor cancer-vertex = ", rule.factor[0][1],
               " differs from vertex-cancer = ", rule.factor[1][0],
               " (pair cutoffs are symmetric)");
  rule_ = rule;
  valid_ = false;
}

bool VerletList::needs_rebuild(const System& sys) const {
  if (!valid_ || sys.n_sites() != counts_.size() || sys.box().version() != box_version_)
    return true;
  const double limit2 = 0.25 * skin_ * skin_;
  const auto& pos = sys.sites().pos;
  const MinimumImage image(sys.box());
  int moved = 0;
#pragma omp parallel for reduction(| : moved) schedule(static) if (parallel_light(pos.size()))
  for (std::size_t i = 0; i < pos.size(); ++i) {
    const double dx = image.x(pos[i][0] - pos_at_build_[i][0]),
                 dy = image.y(pos[i][1] - pos_at_build_[i][1]),
                 dz = image.z(pos[i][2] - pos_at_build_[i][2]);
    moved |= dx * dx + dy * dy + dz * dz > limit2;
  }
  return moved != 0;
}

bool VerletList::update(const System& sys) {
  if (!needs_rebuild(sys)) return false;
  build(sys);
  return true;
}

void VerletList::build(const System& sys) {
  const Sites& s = sys.sites();
  const Box& box = sys.box();
  const std::size_t n = s.size();
  // Classes of the grid: the site kinds. The reach of a class pair is its largest list radius.
  constexpr int kClasses = 2;
  std::array<double, kClasses> max_d{0.0, 0.0};
  std::array<bool, kClasses> present{false, false};
  for (std::size_t i = 0; i < n; ++i) {
    const int k = int(s.kind[i]);
    max_d[k] = std::max(max_d[k], s.diameter[i]);
    present[k] = true;
  }
  std::vector<double> reach(kClasses * kClasses, 0.0);
  double reach_max = skin_, reach_min = INFINITY;
  for (int a = 0; a < kClasses; ++a)
    for (int b = 0; b < kClasses; ++b) {
      if (!present[a] || !present[b]) continue;
      const double r = rule_.of(SiteKind(a), SiteKind(b), max_d[a], max_d[b]) + skin_;
      reach[a * kClasses + b] = r;
      reach_max = std::max(reach_max, r);
      reach_min = std::min(reach_min, r);
    }
  // On periodic axes the minimum image must be unique.
  for (int a = 0; a < 3; ++a)
    if (box.periodic(a) && box.length(a) < 2.0 * reach_max)
      fail_input("box length along ", "xyz"[a], " = ", box.length(a),
                 " is shorter than twice the largest pair cutoff + skin (", reach_max,
                 "); enlarge the box or reduce the skin");
  // Cells half the smallest reach wide: the stencils then follow the spheres of reach closely;
  // at most ~4 cells per site (empty cells cost little: a strip is one contiguous run).
  grid_.setup(box, 0.5 * reach_min, reach, kClasses,
              int(std::min<std::size_t>(4 * n + 64, std::size_t(1) << 24)));
  const int n_cells = grid_.n_cells();
  cell_of_.resize(n);
#pragma omp parallel for schedule(static) if (parallel_light(n))
  for (std::size_t i = 0; i < n; ++i)
    cell_of_[i] = int(s.kind[i]) * n_cells + grid_.cell_of(s.pos[i]);
  // Counting sort by (class, cell) (stable: sites in a bin keep increasing index order), and
  // the sites' data in that order.
  const int n_bins = kClasses * n_cells;
  cell_start_.assign(n_bins + 1, 0);
  for (std::size_t i = 0; i < n; ++i) ++cell_start_[cell_of_[i] + 1];
  for (int c = 0; c < n_bins; ++c) cell_start_[c + 1] += cell_start_[c];
  cell_sites_.resize(n);
  {
    std::vector<int> fill(cell_start_.begin(), cell_start_.end() - 1);
    for (std::size_t i = 0; i < n; ++i) cell_sites_[fill[cell_of_[i]]++] = int(i);
  }
  cell_pos_.resize(n);
  cell_diam_.resize(n);
  cell_body_.resize(n);
  cell_kind_.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    const int j = cell_sites_[p];
    cell_pos_[p] = s.pos[j];
    cell_diam_[p] = s.diameter[j];
    cell_body_[p] = s.body[j];
    cell_kind_[p] = s.kind[j];
  }

  // Each pair is tested once, from the site that comes first in the binned order (the
  // stencils are symmetric): the partner after it goes to the site's row ("upper" entries),
  // then every upper entry (i, j) is mirrored into row j, and the rows are sorted.
  counts_.assign(n, 0);
  upper_.assign(n, 0);
  const MinimumImage image(box);
  for (;;) {
    list_.resize(n * stride_);
    int max_upper = 0;
    std::uint64_t candidates = 0;
    // Bin by bin: the candidate runs are found once per bin and its sites scanned while hot.
#pragma omp parallel reduction(max : max_upper) reduction(+ : candidates) if (parallel_heavy(n))
    {
      std::vector<std::array<int, 2>> runs;
#pragma omp for schedule(dynamic, 64)
      for (int bin = 0; bin < n_bins; ++bin) {
        if (cell_start_[bin] == cell_start_[bin + 1]) continue;
        const int ca = bin / n_cells, c = bin % n_cells;
        runs.clear();
        for (int cb = 0; cb < kClasses; ++cb)
          grid_.for_each_run(c, ca, cb, [&](int c0, int c1) {
            const int p0 = cell_start_[cb * n_cells + c0], p1 = cell_start_[cb * n_cells + c1 + 1];
            if (p0 < p1) runs.push_back({p0, p1});
          });
        for (int q = cell_start_[bin]; q < cell_start_[bin + 1]; ++q) {
          const int i = cell_sites_[q];
          const Vec3 ri = cell_pos_[q];
          const int bi = cell_body_[q];
          const SiteKind ki = cell_kind_[q];
          const double di = cell_diam_[q];
          int* out = &list_[std::size_t(i) * stride_];
          int m = 0;
          for (const auto& run : runs) {
            const int p0 = std::max(run[0], q + 1);  // partners after q only
            candidates += std::uint64_t(std::max(run[1] - p0, 0));
            for (int p = p0; p < run[1]; ++p) {
              if (bi >= 0 && cell_body_[p] == bi) continue;
              const double dx = image.x(ri[0] - cell_pos_[p][0]),
                           dy = image.y(ri[1] - cell_pos_[p][1]),
                           dz = image.z(ri[2] - cell_pos_[p][2]);
              const double rc = rule_.of(ki, cell_kind_[p], di, cell_diam_[p]) + skin_;
              if (dx * dx + dy * dy + dz * dz < rc * rc) {
                if (m < int(stride_)) out[m] = cell_sites_[p];
                ++m;
              }
            }
          }
          upper_[i] = m;
          max_upper = std::max(max_upper, m);
        }
      }
    }
    candidates_ = candidates;
    if (max_upper > int(stride_)) {  // room for the mirrored entries too
      stride_ = 2 * std::size_t(max_upper) + 16;
      continue;
    }
    // Mirror: (i, j) into row j after its upper entries. Each thread fills the rows of its own
    // range of sites, scanning all upper entries in index order (no two threads write a row).
    int max_count = 0;
#pragma omp parallel reduction(max : max_count) if (parallel_heavy(n))
    {
      const int nt = omp_get_num_threads(), t = omp_get_thread_num();
      const int lo = int(n * t / nt), hi = int(n * (t + 1) / nt);
      for (int j = lo; j < hi; ++j) counts_[j] = upper_[j];
      for (std::size_t i = 0; i < n; ++i) {
        const int* row = &list_[i * stride_];
        for (int k = 0; k < upper_[i]; ++k) {
          const int j = row[k];
          if (j < lo || j >= hi) continue;
          const int pos = counts_[j]++;
          if (pos < int(stride_)) list_[std::size_t(j) * stride_ + pos] = int(i);
        }
      }
      for (int j = lo; j < hi; ++j) max_count = std::max(max_count, counts_[j]);
    }
    max_count_ = std::size_t(max_count);
    if (max_count <= int(stride_)) break;
    stride_ = std::size_t(max_count) + 16;
  }
  // Rows in index order: the force sums then do not depend on when the list was built (a run
  // restarted from a checkpoint rebuilds at another step).
#pragma omp parallel for schedule(static) if (parallel_heavy(n))
  for (std::size_t i = 0; i < n; ++i) {
    int* row = &list_[i * stride_];
    std::sort(row, row + counts_[i]);
  }
  pos_at_build_ = s.pos;
  box_version_ = box.version();
  valid_ = true;
  ++builds_;
}

}  // namespace invasim
