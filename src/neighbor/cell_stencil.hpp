#pragma once
// Cell grid and per-class-pair stencils of the Verlet list build (LAMMPS's `neighbor multi`
// idea on one grid). Sites are grouped in classes (e.g. cancer cells and adipocyte vertices);
// each class pair (a, b) has its own reach (largest list radius of such a pair). The cells are
// narrower than the largest reach, and the stencil of (a, b) holds only the cells whose
// nearest point is within reach(a, b) of the centre cell, so a site scans about the volume of
// its own sphere of reach instead of 27 cells sized for the largest pair. A stencil is a list
// of z strips: cells (x + dx, y + dy, z - dz .. z + dz), contiguous in the cell index
// (x * ny + y) * nz + z, so that a strip is one contiguous run of the sites sorted by cell.
#include <array>
#include <vector>

#include "core/box.hpp"

namespace invasim {

class CellStencils {
 public:
  // Grid of cells at least `width` wide (fewer if the axis would hold more than max_per_axis
  // or the grid more than max_cells), and the stencils of the n_classes^2 class pairs with
  // the reaches reach[a * n_classes + b] (symmetric).
  void setup(const Box& box, double width, const std::vector<double>& reach, int n_classes,
             int max_cells);
  int n_cells() const { return nc_[0] * nc_[1] * nc_[2]; }
  const std::array<int, 3>& cells_per_axis() const { return nc_; }
  // Strips in the stencil of class pair (a, b) (bounded by the grid, not by the reach).
  std::size_t strips(int a, int b) const {
    return stencil_[std::size_t(a) * n_classes_ + b].size();
  }
  // Cell of a position (sites slightly beyond a wall join the edge cell).
  int cell_of(const Vec3& r) const;
  // Calls f(c0, c1) for every run of contiguous cells [c0, c1] of the stencil of class pair
  // (a, b) around cell c: each cell of the stencil exactly once.
  template <class F>
  void for_each_run(int c, int a, int b, F&& f) const;

 private:
  struct Strip {
    int dx, dy, dz;  // column (x + dx, y + dy), cells z - dz .. z + dz
  };
  std::array<int, 3> nc_{1, 1, 1};
  std::array<bool, 3> periodic_{false, false, false};
  Vec3 lo_ = Vec3::Zero(), cell_len_ = Vec3::Ones();
  int n_classes_ = 0;
  std::vector<std::vector<Strip>> stencil_;  // per class pair
};

template <class F>
void CellStencils::for_each_run(int c, int a, int b, F&& f) const {
  const int ny = nc_[1], nz = nc_[2];
  const int cx = c / (ny * nz), cy = (c / nz) % ny, cz = c % nz;
  for (const Strip& s : stencil_[std::size_t(a) * n_classes_ + b]) {
    int x = cx + s.dx, y = cy + s.dy;
    if (x < 0 || x >= nc_[0]) {
      if (!periodic_[0]) continue;
      x = (x % nc_[0] + nc_[0]) % nc_[0];
    }
    if (y < 0 || y >= ny) {
      if (!periodic_[1]) continue;
      y = (y % ny + ny) % ny;
    }
    const int column = (x * ny + y) * nz;
    int z0 = cz - s.dz, z1 = cz + s.dz;
    if (periodic_[2]) {
      if (2 * s.dz + 1 >= nz) {  // the whole column, once
        f(column, column + nz - 1);
        continue;
      }
      if (z0 < 0) {  // wraps below: [z0 + nz, nz) and [0, z1]
        f(column + z0 + nz, column + nz - 1);
        z0 = 0;
      } else if (z1 >= nz) {  // wraps above: [z0, nz) and [0, z1 - nz]
        f(column, column + z1 - nz);
        z1 = nz - 1;
      }
    } else {
      z0 = std::max(z0, 0);
      z1 = std::min(z1, nz - 1);
    }
    f(column + z0, column + z1);
  }
}

}  // namespace invasim
