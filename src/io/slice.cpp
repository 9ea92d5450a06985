#include "io/slice.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <unordered_map>

#include "core/errors.hpp"
#include "io/text_format.hpp"

namespace invasim {

namespace {

std::array<int, 2> in_plane_axes(int axis) {
  return axis == 0   ? std::array<int, 2>{1, 2}
         : axis == 1 ? std::array<int, 2>{0, 2}
                     : std::array<int, 2>{0, 1};
}

}  // namespace

SlicePlane parse_slice_plane(std::string_view spec) {
  const std::size_t eq = spec.find('=');
  auto trim = [](std::string_view s) {
    while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
    while (!s.empty() && s.back() == ' ') s.remove_suffix(1);
    return s;
  };
  const std::string_view name = trim(spec.substr(0, eq));
  double value = NAN;
  if (eq != std::string_view::npos)
    if (const auto v = text::parse<double>(trim(spec.substr(eq + 1)))) value = *v;
  if (name.size() != 1 || std::string_view("xyz").find(name[0]) == std::string_view::npos ||
      !std::isfinite(value))
    fail_input("slice '", spec, "': expected x=VALUE, y=VALUE or z=VALUE");
  return {int(name[0] - 'x'), value};
}

std::vector<SlicePolygon> cut_mesh(const std::vector<Vec3>& points,
                                   const std::vector<std::array<int, 3>>& triangles, int axis,
                                   double value) {
  const auto [u, w] = in_plane_axes(axis);
  auto above = [&](int p) { return points[p][axis] - value >= 0.0; };
  auto key = [](int p, int q) {
    return (std::uint64_t(std::min(p, q)) << 32) | std::uint32_t(std::max(p, q));
  };
  // One segment per crossing triangle, between the two mesh edges it crosses.
  struct Segment {
    std::uint64_t e[2];
  };
  std::vector<Segment> segments;
  std::unordered_map<std::uint64_t, std::array<int, 2>> at_edge;  // edge -> its segments
  for (const auto& t : triangles) {
    Segment s{};
    int n = 0;
    for (int k = 0; k < 3; ++k) {
      const int p = t[k], q = t[(k + 1) % 3];
      if (above(p) != above(q) && n < 2) s.e[n++] = key(p, q);
    }
    if (n != 2) continue;
    for (std::uint64_t e : s.e) {
      auto& slots = at_edge.try_emplace(e, std::array<int, 2>{-1, -1}).first->second;
      slots[slots[0] < 0 ? 0 : 1] = int(segments.size());
    }
    segments.push_back(s);
  }
  auto crossing = [&](std::uint64_t e) -> Point2 {
    const int p = int(e >> 32), q = int(e & 0xFFFFFFFFu);
    const double dp = points[p][axis] - value, dq = points[q][axis] - value;
    const double t = dp / (dp - dq);  // dp, dq on opposite sides: dp - dq != 0
    const Vec3 x = points[p] + t * (points[q] - points[p]);
    return {x[u], x[w]};
  };
  // Chain segments through shared edges into polygons.
  std::vector<SlicePolygon> out;
  std::vector<bool> used(segments.size(), false);
  for (std::size_t s0 = 0; s0 < segments.size(); ++s0) {
    if (used[s0]) continue;
    used[s0] = true;
    SlicePolygon poly{-1, {crossing(segments[s0].e[0])}, false};
    const std::uint64_t start = segments[s0].e[0];
    std::uint64_t edge = segments[s0].e[1];
    int prev = int(s0);
    while (true) {
      if (edge == start) {
        poly.closed = true;
        break;
      }
      poly.points.push_back(crossing(edge));
      const auto& pair = at_edge[edge];
      const int next = pair[0] == prev ? pair[1] : pair[0];
      if (next < 0 || used[next]) break;  // an open chain: the mesh is not closed
      used[next] = true;
      edge = segments[next].e[0] == edge ? segments[next].e[1] : segments[next].e[0];
      prev = next;
    }
    // Drop repeated points (a vertex on the plane is reached through two edges).
    auto& pts = poly.points;
    pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
    while (pts.size() > 1 && pts.front() == pts.back()) pts.pop_back();
    if (pts.size() >= 3) out.push_back(std::move(poly));
  }
  return out;
}

Slice cut_frame(const Frame& frame, const SlicePlane& plane) {
  const Box& box = frame.box;
  const int a = plane.axis;
  if (a < 0 || a > 2) fail_input("slice: axis ", a, " must be 0, 1 or 2 (x, y, z)");
  Slice s;
  s.box = box;
  s.step = frame.step;
  s.time = frame.time;
  s.plane = plane;
  const auto [u, w] = in_plane_axes(a);
  s.u_axis = u;
  s.w_axis = w;
  const double L = box.length(a), lo = box.lo()[a], hi = box.hi()[a];
  if (box.periodic(a)) {
    s.plane.value = plane.value - L * std::floor((plane.value - lo) / L);
  } else if (plane.value < lo || plane.value > hi) {
    fail_input("slice ", "xyz"[a], " = ", plane.value, " lies outside the walls [", lo, ", ", hi,
               "]");
  }
  const double v = s.plane.value;

  // Spheres: the nearest periodic image across the plane's axis (radii are far below L/2).
  auto cut_sphere = [&](const Vec3& x, double r, int id, std::vector<SliceDisc>& out) {
    double d = x[a] - v;
    if (box.periodic(a)) d -= L * std::round(d / L);
    if (std::abs(d) < r) out.push_back({id, {x[u], x[w]}, std::sqrt(r * r - d * d)});
  };
  const CellFrame& c = frame.cells;
  for (std::size_t i = 0; i < c.size(); ++i) cut_sphere(c.pos[i], c.radius[i], int(i), s.discs);
  const MeshFrame& m = frame.meshes;
  for (std::size_t p = 0; p < m.point_radius.size() && p < m.points.size(); ++p)
    cut_sphere(m.points[p], m.point_radius[p], int(p), s.vertex_discs);

  // Meshes: each body against every periodic copy of the plane that crosses it.
  const int n_bodies = m.n_bodies();
  std::vector<std::vector<std::array<int, 3>>> tris(n_bodies);
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    tris[m.triangle_body[t]].push_back(m.triangles[t]);
  for (int b = 0; b < n_bodies; ++b) {
    if (tris[b].empty()) continue;
    double min = INFINITY, max = -INFINITY;
    for (const auto& t : tris[b])
      for (int p : t) min = std::min(min, m.points[p][a]), max = std::max(max, m.points[p][a]);
    long k0 = 0, k1 = 0;
    if (box.periodic(a)) {
      k0 = long(std::ceil((min - v) / L));
      k1 = long(std::floor((max - v) / L));
    } else if (v < min || v > max) {
      continue;
    }
    for (long k = k0; k <= k1; ++k)
      for (SlicePolygon& p : cut_mesh(m.points, tris[b], a, v + double(k) * L)) {
        p.body = b;
        s.polygons.push_back(std::move(p));
      }
  }
  return s;
}

}  // namespace invasim
