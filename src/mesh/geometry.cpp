#include "mesh/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

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

// ColumnCrossings::winding_number's answer where a point is too near the mesh to tell.
constexpr int kAmbiguous = std::numeric_limits<int>::min();

// The faces that the vertical line through (px, py) crosses, each with its height and sign
// (+1 where the outward normal points up). The winding number of a point on that line is the
// sum of the signs above it: the same count as the solid angles of winding_number, at the cost
// of one pass over the faces per column instead of an atan2 per face and point. A column
// through a projected edge or vertex, and a point within rounding of a crossing, are left to
// winding_number (kAmbiguous), so the two classify every grid point alike.
class ColumnCrossings {
 public:
  void find(const MeshTopology& topo, const Vec3* x, double px, double py) {
    crossings_.clear();
    degenerate_ = false;
    for (const auto& f : topo.faces()) {
      const Vec3 &a = x[f[0]], &b = x[f[1]], &c = x[f[2]];
      // Twice the signed areas, in the xy plane, of (b, c, p), (c, a, p) and (a, b, p).
      const double da = orient(b, c, px, py), db = orient(c, a, px, py), dc = orient(a, b, px, py);
      // Each side's sign, 0 within rounding of the edge.
      const double tol = 1e-12 * squared_extent(a, b, c);
      const int sa = side(da, tol), sb = side(db, tol), sc = side(dc, tol);
      if (std::min({sa, sb, sc}) < 0 && std::max({sa, sb, sc}) > 0) continue;  // missed
      if (sa == 0 || sb == 0 || sc == 0) {
        degenerate_ = true;  // on or next to a projected edge or vertex
        continue;
      }
      const double area = da + db + dc;
      crossings_.push_back({(da * a[2] + db * b[2] + dc * c[2]) / area, sa > 0 ? 1 : -1});
    }
  }

  // The winding number about (px, py, z), or kAmbiguous.
  int winding_number(double z) const {
    if (degenerate_) return kAmbiguous;
    int w = 0;
    for (const Crossing& c : crossings_) {
      if (std::abs(z - c.z) <= 1e-9 * (1.0 + std::abs(c.z))) return kAmbiguous;
      if (c.z > z) w += c.sign;
    }
    return w;
  }

 private:
  struct Crossing {
    double z;
    int sign;
  };
  static double orient(const Vec3& a, const Vec3& b, double px, double py) {
    return (b[0] - a[0]) * (py - a[1]) - (b[1] - a[1]) * (px - a[0]);
  }
  static int side(double d, double tol) { return d > tol ? 1 : d < -tol ? -1 : 0; }
  static double squared_extent(const Vec3& a, const Vec3& b, const Vec3& c) {
    const double sx = std::max({a[0], b[0], c[0]}) - std::min({a[0], b[0], c[0]});
    const double sy = std::max({a[1], b[1], c[1]}) - std::min({a[1], b[1], c[1]});
    return (sx + sy) * (sx + sy);
  }
  std::vector<Crossing> crossings_;
  bool degenerate_ = false;
};
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
  for (int ix = 0; ix < cells[0]; ++ix) {
    ColumnCrossings column;
    std::vector<int> near;  // the vertices whose spheres the column may meet
    for (int iy = 0; iy < cells[1]; ++iy) {
      const double px = lo[0] + h * (ix + 0.5), py = lo[1] + h * (iy + 0.5);
      column.find(topo, x, px, py);
      near.clear();
      for (int v = 0; v < n; ++v) {
        const double dx = px - x[v][0], dy = py - x[v][1];
        if (dx * dx + dy * dy <= r2 * (1.0 + 1e-9)) near.push_back(v);
      }
      for (int iz = 0; iz < cells[2]; ++iz) {
        const Vec3 p = lo + h * Vec3(ix + 0.5, iy + 0.5, iz + 0.5);
        bool in = false;
        for (std::size_t k = 0; k < near.size() && !in; ++k)
          in = (p - x[near[k]]).squaredNorm() <= r2;
        if (!in && (p - centre).squaredNorm() <= reach2) {
          const int w = column.winding_number(p[2]);
          in = w == kAmbiguous ? winding_number(topo, x, p) > 0.5 : w > 0;
        }
        inside += in;
      }
    }
  }
  return double(inside) * h * h * h;
}

}  // namespace invasim
