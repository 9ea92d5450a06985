#include "mesh/geometry.hpp"

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"

namespace invasim {

Vec3 vertex_centroid(int n, const Vec3* x) {
  Vec3 c = Vec3::Zero();
  for (int i = 0; i < n; ++i) c += x[i];
  return c / double(n);
}

double mesh_volume(const MeshTopology& topo, const Vec3* x) {
  const Vec3 c = vertex_centroid(topo.n_vertices(), x);
  double six_v = 0.0;
  for (const auto& f : topo.faces()) {
    const Vec3 u = x[f[0]] - c, v = x[f[1]] - c, w = x[f[2]] - c;
    six_v += triple_product(u[0], u[1], u[2], v[0], v[1], v[2], w[0], w[1], w[2]);
  }
  return six_v / 6.0;
}

double face_area(const MeshTopology& topo, const Vec3* x, int k) {
  const auto& f = topo.faces()[k];
  const Vec3 e = x[f[1]] - x[f[0]], g = x[f[2]] - x[f[0]];
  return 0.5 * twice_triangle_area(e[0], e[1], e[2], g[0], g[1], g[2]);
}

double mesh_area(const MeshTopology& topo, const Vec3* x) {
  double s = 0.0;
  for (int k = 0; k < topo.n_faces(); ++k) s += face_area(topo, x, k);
  return s;
}

double shape_parameter(double area, double volume) {
  return std::pow(area, 1.5) / (6.0 * std::sqrt(M_PI) * volume);
}

void add_volume_gradient(const MeshTopology& topo, const Vec3* x, double scale, Vec3* grad) {
  // V = (1/6) sum_f a.(b x c); dV/da = (1/6) (b x c), cyclic. Translation invariance of the
  // closed-mesh sum lets us use positions relative to the centroid for accuracy.
  const Vec3 c = vertex_centroid(topo.n_vertices(), x);
  const double s = scale / 6.0;
  for (const auto& f : topo.faces()) {
    const Vec3 a = x[f[0]] - c, b = x[f[1]] - c, d = x[f[2]] - c;
    grad[f[0]] += s * b.cross(d);
    grad[f[1]] += s * d.cross(a);
    grad[f[2]] += s * a.cross(b);
  }
}

namespace {
// Winding number of a closed mesh about p (1 inside, 0 outside) from signed solid angles
// (Van Oosterom & Strackee's formula for a triangle's solid angle).
double winding_number(const MeshTopology& topo, const Vec3* x, const Vec3& p) {
  double omega = 0.0;
  for (const auto& f : topo.faces()) {
    const Vec3 a = x[f[0]] - p, b = x[f[1]] - p, c = x[f[2]] - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double num = a.dot(b.cross(c));
    const double den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    omega += 2.0 * std::atan2(num, den);
  }
  return omega / (4.0 * M_PI);
}
}  // namespace

double union_volume(const MeshTopology& topo, const Vec3* x, double vertex_diameter, double h) {
  const int n = topo.n_vertices();
  const double r = 0.5 * vertex_diameter, r2 = r * r;
  Vec3 lo = x[0], hi = x[0];
  for (int i = 1; i < n; ++i) {
    lo = lo.cwiseMin(x[i]);
    hi = hi.cwiseMax(x[i]);
  }
  lo.array() -= r;
  hi.array() += r;
  // The grid's size is checked in doubles before the cast to int: a tiny spacing
  // would overflow int and run for days.
  const Vec3 extent = ((hi - lo) / h).array().ceil();
  const double points = extent.prod();
  if (!(h > 0.0) || !(points <= kMaxUnionVolumeGridPoints))
    fail_input(
        "volume_grid = ", h, " gives ", points, " grid points over the mesh's ", "bounding box (",
        (hi - lo).transpose(), "); the limit is ", kMaxUnionVolumeGridPoints,
        " points, i.e. volume_grid >= ", std::cbrt((hi - lo).prod() / kMaxUnionVolumeGridPoints));
  const Vec3i cells = extent.cast<int>();
  // Points beyond the farthest vertex from the centroid are outside the mesh (no winding
  // number needed there).
  const Vec3 centre = vertex_centroid(n, x);
  double reach2 = 0.0;
  for (int i = 0; i < n; ++i) reach2 = std::max(reach2, (x[i] - centre).squaredNorm());
  long inside = 0;
#pragma omp parallel for reduction(+ : inside) schedule(static)
  for (int ix = 0; ix < cells[0]; ++ix)
    for (int iy = 0; iy < cells[1]; ++iy)
      for (int iz = 0; iz < cells[2]; ++iz) {
        const Vec3 p = lo + h * Vec3(ix + 0.5, iy + 0.5, iz + 0.5);
        bool in = false;
        for (int v = 0; v < n && !in; ++v) in = (p - x[v]).squaredNorm() <= r2;
        if (!in && (p - centre).squaredNorm() <= reach2) in = winding_number(topo, x, p) > 0.5;
        inside += in;
      }
  return double(inside) * h * h * h;
}

}  // namespace invasim
