#include "mesh/plane_cut.hpp"

#include <algorithm>
#include <cstdint>
#include <unordered_map>

#include "core/errors.hpp"

namespace invasim {

std::vector<CutLoop> cut_by_plane(const Vec3* x, std::span<const std::array<int, 3>> triangles,
                                  const Plane& plane) {
  auto dist = [&](int p) { return (x[p] - plane.point).dot(plane.normal); };
  auto above = [&](int p) { return dist(p) >= 0.0; };  // the on-plane rule

  // One cut point per crossed edge, shared by the edge's two faces.
  std::unordered_map<std::uint64_t, int> point_of_edge;
  std::vector<Vec3> points;
  auto cut = [&](int a, int b) {
    if (a > b) std::swap(a, b);
    const std::uint64_t key = (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b);
    auto [it, fresh] = point_of_edge.try_emplace(key, int(points.size()));
    if (fresh) {
      const double da = dist(a), db = dist(b);  // opposite sides: da - db != 0
      points.push_back(x[a] + da / (da - db) * (x[b] - x[a]));
    }
    return it->second;
  };
  // In an outward-oriented face the cut runs from the edge whose direction (in face order)
  // goes from + to - towards the edge going from - to +; each cut point of a closed mesh
  // then starts one segment and ends one (its edge's two faces see it in opposite
  // directions), so following the segments closes every loop.
  std::vector<int> next, prev;
  for (const auto& f : triangles) {
    int from = -1, to = -1;
    for (int e = 0; e < 3; ++e) {
      const int a = f[e], b = f[(e + 1) % 3];
      const bool ua = above(a), ub = above(b);
      if (ua && !ub) from = cut(a, b);
      if (!ua && ub) to = cut(a, b);
    }
    if (from < 0) continue;
    next.resize(points.size(), -1);
    prev.resize(points.size(), -1);
    if (next[from] >= 0 || prev[to] >= 0)
      fail_simulation("plane cut: the mesh is not consistently oriented");
    next[from] = to;
    prev[to] = from;
  }
  next.resize(points.size(), -1);
  prev.resize(points.size(), -1);

  std::vector<CutLoop> loops;
  std::vector<char> used(points.size(), 0);
  auto trace = [&](int start, bool closed) {
    CutLoop loop{{}, closed};
    for (int p = start; p >= 0 && !used[p]; p = next[p]) {
      used[p] = 1;
      loop.points.push_back(points[p]);
    }
    auto& pts = loop.points;  // merge the repeated points of on-plane vertices
    pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
    while (closed && pts.size() > 1 && pts.front() == pts.back()) pts.pop_back();
    if (pts.size() >= 3) loops.push_back(std::move(loop));
  };
  for (std::size_t p = 0; p < points.size(); ++p)  // open chains: where the mesh has an edge
    if (prev[p] < 0) trace(int(p), false);
  for (std::size_t p = 0; p < points.size(); ++p)
    if (!used[p]) trace(int(p), true);
  return loops;
}

}  // namespace invasim
