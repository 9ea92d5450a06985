#include "neighbor/verlet_list.hpp"
#include "core/parallel.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "core/errors.hpp"
#include "core/team_barrier.hpp"
#include "neighbor/candidate_lanes.hpp"

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

void VerletList::prepare_update(const System& sys) {
  // (A new storage layout moves the sites to other slots: the rows name slots.)
  forced_ = !valid_ || sys.n_sites() != counts_.size() || sys.box().version() != box_version_ ||
            sys.layout_id() != layout_id_;
  if (forced_) {
    valid_ = false;  // (stays forced if the region does not run, e.g. another term throws)
    setup_grid(sys);
  }
  grow_to_team(slots_);
}

bool VerletList::update(const System& sys) {
  prepare_update(sys);
  bool rebuilt = false;
#pragma omp parallel if (parallel_heavy(sys.n_sites()))
  {
    const bool r = update_team(sys);
    if (team_leader()) rebuilt = r;
  }
  return rebuilt;
}

void VerletList::build(const System& sys) {
  valid_ = false;
  prepare_update(sys);
#pragma omp parallel if (parallel_heavy(sys.n_sites()))
  update_team(sys);
}

bool VerletList::update_team(const System& sys) {
  if (!forced_ && !moved_team(sys)) return false;
  build_team(sys);
  return true;
}

bool VerletList::moved_team(const System& sys) const {
  // Every thread tests all sites (a few microseconds: one vectorised pass over positions that
  // are in cache) and so reaches the same answer without a barrier; sharing the loop would
  // need one to combine the threads' flags, and a barrier at which a thread sleeps costs a
  // futex wake-up (docs/performance.md, "The parallel step").
  const double limit2 = 0.25 * skin_ * skin_;
  const auto& pos = sys.sites().pos;
  const MinimumImage image(sys.box());
  int moved = 0;
  for (std::size_t i = 0; i < pos.size(); ++i) {
    const double dx = image.x(pos[i][0] - pos_at_build_[i][0]),
                 dy = image.y(pos[i][1] - pos_at_build_[i][1]),
                 dz = image.z(pos[i][2] - pos_at_build_[i][2]);
    moved |= dx * dx + dy * dy + dz * dz > limit2;
  }
  return moved != 0;
}

void VerletList::setup_grid(const System& sys) {
  const Sites& s = sys.sites();
  const Box& box = sys.box();
  const std::size_t n = s.size();
  // Classes of the grid: the site kinds. The reach of a class pair is its largest list radius.
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
  // Cells one smallest reach wide: a bin's candidate runs are found once for the several
  // sites it holds, and the runs are long enough for the vectorised test. Half as wide, the
  // stencils follow the spheres of reach closer (half the candidates) but a bin holds one
  // site or none and finding its runs cost more than the candidates saved: 1-thread rates
  // 3.8e6 -> 4.8e6 site-steps/s for hot spheres (N = 7000, kT = 0.05, a build every 3
  // steps), 1.13e7 -> 1.22e7 cold (N = 1500), the full system about 8 % (docs/performance.md).
  grid_.setup(box, reach_min, reach, kClasses,
              int(std::min<std::size_t>(4 * n + 64, std::size_t(1) << 24)));
  // (The grid, the classes' reach and the site count stay as they are until the next forced
  // build: the diameters and kinds change only with the sites.)
  cell_of_.resize(n);
  cell_sites_.resize(n);
  cell_x_.resize(n);
  cell_y_.resize(n);
  cell_z_.resize(n);
  cell_diam_.resize(n);
  cell_body_.resize(n);
  counts_.assign(n, 0);
  upper_.assign(n, 0);
  pos_at_build_.resize(n);
  list_.resize(n * stride_);
}

void VerletList::bin_sites(const Sites& s) {
  const std::size_t n = s.size();
  // Counting sort by (class, cell) (stable: sites in a bin keep increasing index order), and
  // the sites' data in that order.
  const int n_bins = kClasses * grid_.n_cells();
  cell_start_.assign(n_bins + 1, 0);
  for (std::size_t i = 0; i < n; ++i) ++cell_start_[cell_of_[i] + 1];
  for (int c = 0; c < n_bins; ++c) cell_start_[c + 1] += cell_start_[c];
  {
    std::vector<int> fill(cell_start_.begin(), cell_start_.end() - 1);
    for (std::size_t i = 0; i < n; ++i) cell_sites_[fill[cell_of_[i]]++] = int(i);
  }
  for (std::size_t p = 0; p < n; ++p) {
    const int j = cell_sites_[p];
    cell_x_[p] = s.pos[j][0];
    cell_y_[p] = s.pos[j][1];
    cell_z_[p] = s.pos[j][2];
    cell_diam_[p] = s.diameter[j];
    cell_body_[p] = s.body[j];
  }
}

void VerletList::build_team(const System& sys) {
  const Sites& s = sys.sites();
  const std::size_t n = s.size();
  const int n_cells = grid_.n_cells();
  const int n_bins = kClasses * n_cells;
  const int me = omp_get_thread_num(), nt = omp_get_num_threads();
#pragma omp for schedule(static) nowait
  for (std::size_t i = 0; i < n; ++i)
    cell_of_[i] = int(s.kind[i]) * n_cells + grid_.cell_of(s.pos[i]);
  team_barrier();
#pragma omp single nowait
  bin_sites(s);
  team_barrier();

  // Each pair is tested once, from the site that comes first in the binned order (the
  // stencils are symmetric): the partner after it goes to the site's row ("upper" entries),
  // then every upper entry (i, j) is mirrored into row j, and the rows are sorted. The
  // branches below (stride overflow) are taken from shared values read after a barrier, so
  // every thread takes the same one.
  const MinimumImage image(sys.box());
  int max_count = 0;
  std::uint64_t candidates = 0;
  for (;;) {
    const std::size_t stride = stride_;  // (read before the barrier at which it may change)
    int max_upper = 0;
    candidates = 0;
    {
      // Bin by bin: the candidate runs (of one class each) are found once per bin and its
      // sites scanned while hot; a run's candidates are tested and compacted in one
      // branch-free pass.
      std::vector<std::array<int, 3>> runs;
      const double hx = image.half(0), hy = image.half(1), hz = image.half(2);
      const double lx = image.length(0), ly = image.length(1), lz = image.length(2);
      const double* __restrict px = cell_x_.data();
      const double* __restrict py = cell_y_.data();
      const double* __restrict pz = cell_z_.data();
      const double* __restrict pd = cell_diam_.data();
      const int* __restrict pb = cell_body_.data();
      const double skin = skin_;
#pragma omp for schedule(dynamic, 64) nowait
      for (int bin = 0; bin < n_bins; ++bin) {
        if (cell_start_[bin] == cell_start_[bin + 1]) continue;
        const int ca = bin / n_cells, c = bin % n_cells;
        runs.clear();
        for (int cb = 0; cb < kClasses; ++cb)
          grid_.for_each_run(c, ca, cb, [&](int c0, int c1) {
            const int p0 = cell_start_[cb * n_cells + c0], p1 = cell_start_[cb * n_cells + c1 + 1];
            if (p0 < p1) runs.push_back({p0, p1, cb});
          });
        for (int q = cell_start_[bin]; q < cell_start_[bin + 1]; ++q) {
          const int i = cell_sites_[q];
          const double xi = px[q], yi = py[q], zi = pz[q], di = pd[q];
          const int bi = pb[q];
          int* out = &list_[std::size_t(i) * stride];
          const int last = int(stride) - 1;
          int m = 0;
          for (const auto& run : runs) {
            const int p0 = std::max(run[0], q + 1), p1 = run[1];  // partners after q only
            if (p0 >= p1) continue;
            candidates += std::uint64_t(p1 - p0);
            const double half_factor = 0.5 * rule_.factor[int(ca)][run[2]];
#if INVASIM_CANDIDATE_LANES
            if (m + (p1 - p0) + 7 <= int(stride)) {  // room for every candidate (else below)
              const neighbor_detail::CandidateSite site{xi, yi, zi, di, bi,          hx,  hy,
                                                        hz, lx, ly, lz, half_factor, skin};
              m = neighbor_detail::keep_candidates_lanes(site, px, py, pz, pd, pb,
                                                         cell_sites_.data(), p0, p1, out, m);
              continue;
            }
#endif
            // Without the lanes (no AVX-512, or no room in the row), one branch-free pass (runs
            // are a few candidates long: a compiled vector loop would run mostly in its scalar
            // remainder): the minimum image as arithmetic on the comparisons (d - l or d + l
            // exactly where the ternary gives them, d itself otherwise; a walled axis has l = 0
            // and an infinite half), and the compaction, which writes the slot at the row's
            // count whether or not the pair is kept (it lies inside the row, and a row that
            // overflows its stride is redone).
            auto nearest_image = [](double d, double half, double len) {
              return d - len * double(d > half) + len * double(d < -half);
            };
            for (int p = p0; p < p1; ++p) {
              const double dx = nearest_image(xi - px[p], hx, lx),
                           dy = nearest_image(yi - py[p], hy, ly),
                           dz = nearest_image(zi - pz[p], hz, lz);
              const double rc = half_factor * (di + pd[p]) + skin;
              const int keep = (dx * dx + dy * dy + dz * dz < rc * rc) & ((bi < 0) | (pb[p] != bi));
              out[std::min(m, last)] = cell_sites_[p];
              m += keep;
            }
          }
          upper_[i] = m;
          counts_[i] = m;  // the mirrored entries follow
          max_upper = std::max(max_upper, m);
        }
      }
    }
    slots_[me].max_upper = max_upper;
    slots_[me].candidates = candidates;
    team_barrier();
    max_upper = 0;
    candidates = 0;
    for (int t = 0; t < nt; ++t) {
      max_upper = std::max(max_upper, slots_[t].max_upper);
      candidates += slots_[t].candidates;
    }
    if (max_upper > int(stride)) {  // room for the mirrored entries too
#pragma omp single nowait
      {
        stride_ = 2 * std::size_t(max_upper) + 16;
        list_.resize(n * stride_);
      }
      team_barrier();
      continue;
    }
    // Mirror: each thread takes the upper entries (i, j) of its own rows i and appends i to
    // row j at the position its counter hands out (atomically when other threads share the
    // rows); the order within a row does not matter, the rows are sorted below. A row's
    // count is its upper entries plus its mirrored ones, so the longest row is the longest
    // upper part or the largest position handed out.
    max_count = max_upper;
    auto mirror = [&](auto atomic) {
#pragma omp for schedule(static) nowait
      for (std::size_t i = 0; i < n; ++i) {
        const int* row = &list_[i * stride];
        for (int k = 0; k < upper_[i]; ++k) {
          const int j = row[k];
          int pos;
          if constexpr (decltype(atomic)::value) {
#pragma omp atomic capture
            pos = counts_[j]++;
          } else {
            pos = counts_[j]++;
          }
          if (pos < int(stride)) list_[std::size_t(j) * stride + pos] = int(i);
          max_count = std::max(max_count, pos + 1);
        }
      }
    };
    if (nt > 1)
      mirror(std::true_type{});
    else
      mirror(std::false_type{});
    slots_[me].max_count = max_count;
    team_barrier();
    for (int t = 0; t < nt; ++t) max_count = std::max(max_count, slots_[t].max_count);
    if (max_count <= int(stride)) break;
#pragma omp single nowait
    {
      stride_ = std::size_t(max_count) + 16;
      list_.resize(n * stride_);
    }
    team_barrier();
  }
  if (me == 0) {  // (read by the caller after the barrier below)
    max_count_ = std::size_t(max_count);
    candidates_ = candidates;
    box_version_ = sys.box().version();
    layout_id_ = sys.layout_id();
    valid_ = true;
    forced_ = false;
    ++builds_;
  }
  // Rows in index order: the force sums then do not depend on when the list was built (a run
  // restarted from a checkpoint rebuilds at another step).
#pragma omp for schedule(static) nowait
  for (std::size_t i = 0; i < n; ++i) {
    int* row = &list_[i * stride_];
    std::sort(row, row + counts_[i]);
    pos_at_build_[i] = s.pos[i];
  }
  team_barrier();
}

}  // namespace invasim
