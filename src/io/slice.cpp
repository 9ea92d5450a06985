#include "io/slice.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/errors.hpp"
#include "io/text_format.hpp"
#include "mesh/plane_cut.hpp"

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
  Vec3 normal = Vec3::Zero();
  normal[axis] = 1.0;
  std::vector<SlicePolygon> out;
  for (const CutLoop& loop :
       cut_by_plane(points.data(), triangles, Plane{value * normal, normal})) {
    SlicePolygon poly{-1, {}, loop.closed};
    for (const Vec3& x : loop.points) poly.points.push_back({x[u], x[w]});
    out.push_back(std::move(poly));
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
    // One period either side of the box is wrapped (a plane given in unwrapped coordinates);
    // farther planes are refused: wrapping them loses the value's digits (z = -1e300 would
    // land anywhere, most likely outside the box, and cut nothing).
    if (!(plane.value >= lo - L && plane.value <= hi + L))
      fail_input("slice ", "xyz"[a], " = ", plane.value, " lies outside the box [", lo, ", ", hi,
                 "] by more than one period of the periodic ", "xyz"[a],
                 " axis (planes within one period are wrapped into the box)");
    s.plane.value = plane.value - L * std::floor((plane.value - lo) / L);
    if (s.plane.value >= hi) s.plane.value = lo;  // round-off of a value just below lo
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
  const bool oriented = c.orient.size() == c.size();
  for (std::size_t i = 0; i < c.size(); ++i) {
    const std::size_t before = s.discs.size();
    cut_sphere(c.pos[i], c.radius[i], int(i), s.discs);
    if (oriented && s.discs.size() > before) s.discs.back().active = c.orient[i].norm() > 0.5;
  }
  const MeshFrame& m = frame.meshes;
  std::vector<int> body_of_point(m.points.size(), -1);
  for (std::size_t t = 0; t < m.triangles.size() && t < m.triangle_body.size(); ++t)
    for (int p : m.triangles[t])
      if (p >= 0 && std::size_t(p) < body_of_point.size()) body_of_point[p] = m.triangle_body[t];
  for (std::size_t p = 0; p < m.point_radius.size() && p < m.points.size(); ++p) {
    const std::size_t before = s.vertex_discs.size();
    cut_sphere(m.points[p], m.point_radius[p], int(p), s.vertex_discs);
    if (s.vertex_discs.size() > before) s.vertex_discs.back().body = body_of_point[p];
  }

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
