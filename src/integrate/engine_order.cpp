#include "integrate/engine_order.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include "forces/contact_half.hpp"

namespace invasim {

std::vector<int> spatial_order(const System& sys) {
  const Sites& s = sys.sites();
  const std::size_t n = s.size();
  double width = 0.0;
  for (double d : s.diameter) width = std::max(width, d);
  // The grid: the box on periodic axes, the sites' span between walls; axes ordered slab axis
  // first (slowest), then the other two.
  const int major = slab_axis(sys, 2);
  const int axes[3] = {major, (major + 1) % 3, (major + 2) % 3};
  double lo[3], per_length[3];  // lower end and cells per unit length of each grid axis
  for (int q = 0; q < 3; ++q) {
    const int a = axes[q];
    double l = sys.box().lo()[a], len = sys.box().length(a);
    if (!sys.box().periodic(a)) {
      l = INFINITY;
      double h = -INFINITY;
      for (const Vec3& r : s.pos) l = std::min(l, r[a]), h = std::max(h, r[a]);
      len = n ? h - l : 0.0;
    }
    // At most 1024 cells per axis (the keys then fit in 64 bits whatever the box).
    const double cells = std::clamp(std::floor(len / std::max(width, 1e-300)), 1.0, 1024.0);
    lo[q] = l;
    per_length[q] = len > 0.0 ? cells / len : 0.0;
  }
  // (key, permanent index) of every site, sorted.
  std::vector<std::pair<std::uint64_t, int>> key(n);
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3& r = s.pos[k];
    std::uint64_t cell = std::uint64_t(s.kind[k]);
    for (int q = 0; q < 3; ++q) {
      const double c = std::floor((r[axes[q]] - lo[q]) * per_length[q]);
      cell = cell * 1025 + std::uint64_t(std::clamp(c, 0.0, 1024.0));
    }
    key[k] = {cell, sys.site_of_slot(int(k))};
  }
  std::sort(key.begin(), key.end());
  std::vector<int> order(n);
  for (std::size_t k = 0; k < n; ++k) order[k] = key[k].second;
  return order;
}

EngineLayoutScope::EngineLayoutScope(System& sys) : sys_(sys) {
  if (sys.engine_layout()) return;
  if (sys.engine_order().size() != sys.n_sites()) sys.set_engine_order(spatial_order(sys));
  sys.to_engine();
  entered_ = true;
}

EngineLayoutScope::~EngineLayoutScope() {
  if (entered_) sys_.to_user();
}

}  // namespace invasim
