#include "neighbor/verlet_list.hpp"
#include "core/parallel.hpp"

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"

namespace invasim {

VerletList::VerletList(double skin) : skin_(skin) {
  if (!(skin >= 0.0)) fail_input("neighbour list: skin = ", skin, " must be >= 0");
}

void VerletList::set_cutoff_rule(const CutoffRule& rule) {
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

namespace {

// The cells around cell (cx, cy, cz), deduplicated (an axis with fewer than 3 cells wraps
// onto itself) and sorted; returns their number.
int stencil(int cx, int cy, int cz, const std::array<int, 3>& nc, const std::array<bool, 3>& per,
            int* cells) {
  int n_nb = 0;
  for (int dx = -1; dx <= 1; ++dx) {
    int x = cx + dx;
    if (x < 0 || x >= nc[0]) {
      if (!per[0]) continue;
      x = (x + nc[0]) % nc[0];
    }
    for (int dy = -1; dy <= 1; ++dy) {
      int y = cy + dy;
      if (y < 0 || y >= nc[1]) {
        if (!per[1]) continue;
        y = (y + nc[1]) % nc[1];
      }
      for (int dz = -1; dz <= 1; ++dz) {
        int z = cz + dz;
        if (z < 0 || z >= nc[2]) {
          if (!per[2]) continue;
          z = (z + nc[2]) % nc[2];
        }
        const int c = (x * nc[1] + y) * nc[2] + z;
        if (std::find(cells, cells + n_nb, c) == cells + n_nb) cells[n_nb++] = c;
      }
    }
  }
  std::sort(cells, cells + n_nb);
  return n_nb;
}

}  // namespace

void VerletList::build(const System& sys) {
  const Sites& s = sys.sites();
  const Box& box = sys.box();
  const std::size_t n = s.size();
  double max_d = 0.0;
  for (double d : s.diameter) max_d = std::max(max_d, d);
  double max_factor = 0.0;
  for (const auto& row : rule_.factor)
    for (double f : row) max_factor = std::max(max_factor, f);
  const double reach = max_factor * max_d + skin_;  // largest list radius of any pair

  // Cell grid: cells at least `reach` wide. On periodic axes the minimum image must be unique.
  std::array<int, 3> nc;
  Vec3 cell_len;
  for (int a = 0; a < 3; ++a) {
    const double len = box.length(a);
    if (box.periodic(a) && len < 2.0 * reach)
      fail_input("box length along ", "xyz"[a], " = ", len, " is shorter than twice the ",
                 "largest pair cutoff + skin (", reach, "); enlarge the box or reduce the skin");
    nc[a] = std::max(1, int(std::floor(len / std::max(reach, 1e-12))));
    nc[a] = std::min(nc[a], 1024);
    cell_len[a] = len / nc[a];
  }
  const int n_cells = nc[0] * nc[1] * nc[2];
  cell_of_.resize(n);
  auto axis_cell = [&](double x, int a) {
    int c = int(std::floor((x - box.lo()[a]) / cell_len[a]));
    return std::clamp(c, 0, nc[a] - 1);  // sites slightly beyond a wall join the edge cell
  };
#pragma omp parallel for schedule(static) if (parallel_light(n))
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& r = s.pos[i];
    cell_of_[i] = (axis_cell(r[0], 0) * nc[1] + axis_cell(r[1], 1)) * nc[2] + axis_cell(r[2], 2);
  }
  // Counting sort (stable: sites in a cell keep increasing index order), and the sites' data
  // in cell order.
  cell_start_.assign(n_cells + 1, 0);
  for (std::size_t i = 0; i < n; ++i) ++cell_start_[cell_of_[i] + 1];
  for (int c = 0; c < n_cells; ++c) cell_start_[c + 1] += cell_start_[c];
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

  counts_.assign(n, 0);
  const std::array<bool, 3> per = box.periodic();
  const MinimumImage image(box);
  bool overflow = true;
  while (overflow) {
    overflow = false;
    list_.resize(n * stride_);
    int max_count = 0;
    // Cell by cell: the stencil is found once per cell and its sites are scanned while hot.
#pragma omp parallel for schedule(dynamic, 16) reduction(max : max_count) if (parallel_heavy(n))
    for (int c = 0; c < n_cells; ++c) {
      if (cell_start_[c] == cell_start_[c + 1]) continue;
      int cells[27];
      const int n_nb = stencil(c / (nc[1] * nc[2]), (c / nc[2]) % nc[1], c % nc[2], nc, per, cells);
      for (int q = cell_start_[c]; q < cell_start_[c + 1]; ++q) {
        const int i = cell_sites_[q];
        const Vec3 ri = cell_pos_[q];
        const int bi = cell_body_[q];
        const SiteKind ki = cell_kind_[q];
        const double di = cell_diam_[q];
        int* out = &list_[std::size_t(i) * stride_];
        int m = 0;
        for (int k = 0; k < n_nb; ++k)
          for (int p = cell_start_[cells[k]]; p < cell_start_[cells[k] + 1]; ++p) {
            if (p == q || (bi >= 0 && cell_body_[p] == bi)) continue;
            const double dx = image.x(ri[0] - cell_pos_[p][0]),
                         dy = image.y(ri[1] - cell_pos_[p][1]),
                         dz = image.z(ri[2] - cell_pos_[p][2]);
            const double rc = rule_.of(ki, cell_kind_[p], di, cell_diam_[p]) + skin_;
            if (dx * dx + dy * dy + dz * dz < rc * rc) {
              if (m < int(stride_)) out[m] = cell_sites_[p];
              ++m;
            }
          }
        // Rows in index order: the force sums then do not depend on when the list was built
        // (a run restarted from a checkpoint rebuilds at another step).
        if (m <= int(stride_)) std::sort(out, out + m);
        counts_[i] = m;
        max_count = std::max(max_count, m);
      }
    }
    if (max_count > int(stride_)) {
      stride_ = std::size_t(max_count) + 16;
      overflow = true;
    }
    max_count_ = std::size_t(max_count);
  }
  pos_at_build_ = s.pos;
  box_version_ = box.version();
  valid_ = true;
  ++builds_;
}

}  // namespace invasim
