#include "neighbor/cell_stencil.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace invasim {

namespace {

// Offset d of a periodic axis with n cells is kept only if no other offset of [-k, k] reaches
// the same cell with a smaller |d| (ties: the negative one), so that every cell is scanned once
// and, as its gap is the smallest, with the widest strip.
bool canonical(int d, int k, int n, bool periodic) {
  if (!periodic) return true;
  for (int e = d - n; e >= -k; e -= n)
    if (std::abs(e) <= std::abs(d)) return false;
  for (int e = d + n; e <= k; e += n)
    if (std::abs(e) < std::abs(d)) return false;
  return true;
}

}  // namespace

void CellStencils::setup(const Box& box, double width, const std::vector<double>& reach,
                         int n_classes, int max_cells) {
  lo_ = box.lo();
  periodic_ = box.periodic();
  double max_len = 0.0;
  for (int a = 0; a < 3; ++a) max_len = std::max(max_len, box.length(a));
  width = std::max(width, 1e-12);
  for (;;) {  // widen the cells until the grid is small enough
    long long total = 1;
    for (int a = 0; a < 3; ++a) {
      nc_[a] = int(std::clamp(std::floor(box.length(a) / width), 1.0, 1024.0));
      cell_len_[a] = box.length(a) / nc_[a];
      total *= nc_[a];
    }
    if (total <= std::max(max_cells, 1)) break;
    width *= 1.25;
  }
  n_classes_ = n_classes;
  stencil_.assign(std::size_t(n_classes) * n_classes, {});
  // Gap along an axis between the centre cell and the cell d away (lower bound of the
  // distance of two sites in them); a tiny margin covers the rounding of the cell assignment.
  const double margin = 1e-9 * max_len;
  auto gap = [&](int d, int a) { return std::max(0, std::abs(d) - 1) * cell_len_[a]; };
  // Offsets along axis a that a reach r needs: never more than the grid has (a periodic axis
  // wraps within n offsets, a wall axis has n - 1), whatever r / cell length is. A tissue that
  // blows up can squeeze a wall axis to a sliver, where r / cell length reaches 1e9 and more.
  auto reach_in_cells = [&](double r, int a) {
    const int limit = periodic_[a] ? nc_[a] : nc_[a] - 1;
    const double k = std::ceil(r / cell_len_[a]);
    return k <= double(limit) ? int(k) : limit;  // also for NaN
  };
  for (int ca = 0; ca < n_classes; ++ca)
    for (int cb = 0; cb < n_classes; ++cb) {
      const double r = reach[std::size_t(ca) * n_classes + cb] + margin;
      if (!(r > 0.0)) continue;
      std::array<int, 3> k;
      for (int a = 0; a < 3; ++a) k[a] = reach_in_cells(r, a);
      auto& st = stencil_[std::size_t(ca) * n_classes + cb];
      for (int dx = -k[0]; dx <= k[0]; ++dx) {
        if (!canonical(dx, k[0], nc_[0], periodic_[0])) continue;
        for (int dy = -k[1]; dy <= k[1]; ++dy) {
          if (!canonical(dy, k[1], nc_[1], periodic_[1])) continue;
          const double gxy = gap(dx, 0) * gap(dx, 0) + gap(dy, 1) * gap(dy, 1);
          if (!(gxy < r * r)) continue;
          int dz = 0;
          while (dz < k[2] && gxy + gap(dz + 1, 2) * gap(dz + 1, 2) < r * r) ++dz;
          st.push_back({dx, dy, dz});
        }
      }
    }
}

int CellStencils::cell_of(const Vec3& r) const {
  int c[3];
  for (int a = 0; a < 3; ++a) {  // clamped before the conversion (a far or NaN position: 0)
    const double x = std::floor((r[a] - lo_[a]) / cell_len_[a]);
    c[a] = x >= 0.0 ? int(std::min(x, double(nc_[a] - 1))) : 0;
  }
  return (c[0] * nc_[1] + c[1]) * nc_[2] + c[2];
}

}  // namespace invasim
