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
  // Each kind's grid: cells one of its largest diameter wide (a cell then holds about one site
  // of the kind), over the box on periodic axes and the sites' span between walls; the axes
  // ordered slab axis first (slowest), then the other two.
  constexpr int kKinds = 2;
  double width[kKinds] = {0.0, 0.0};
  for (std::size_t k = 0; k < n; ++k)
    width[int(s.kind[k])] = std::max(width[int(s.kind[k])], s.diameter[k]);
  const int major = slab_axis(sys, 2);
  const int axes[3] = {major, (major + 1) % 3, (major + 2) % 3};
  double lo[3], len[3];
  for (int q = 0; q < 3; ++q) {
    const int a = axes[q];
    lo[q] = sys.box().lo()[a];
    len[q] = sys.box().length(a);
    if (!sys.box().periodic(a) && n > 0) {
      double l = INFINITY, h = -INFINITY;
      for (const Vec3& r : s.pos) l = std::min(l, r[a]), h = std::max(h, r[a]);
      lo[q] = l;
      len[q] = h - l;
    }
  }
  // Cells per unit length of each kind and axis, at most 1024 per axis (the keys then fit in
  // 64 bits whatever the box).
  double per_length[kKinds][3];
  for (int c = 0; c < kKinds; ++c)
    for (int q = 0; q < 3; ++q) {
      const double cells = std::clamp(std::floor(len[q] / std::max(width[c], 1e-300)), 1.0, 1024.0);
      per_length[c][q] = len[q] > 0.0 ? cells / len[q] : 0.0;
    }
  // (key, permanent index) of every site, sorted: kind, then cell, then permanent index.
  std::vector<std::pair<std::uint64_t, int>> key(n);
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3& r = s.pos[k];
    const int c = int(s.kind[k]);
    std::uint64_t cell = std::uint64_t(c);
    for (int q = 0; q < 3; ++q) {
      const double x = std::floor((r[axes[q]] - lo[q]) * per_length[c][q]);
      cell = cell * 1025 + std::uint64_t(x >= 0.0 ? std::min(x, 1024.0) : 0.0);  // NaN: 0
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
