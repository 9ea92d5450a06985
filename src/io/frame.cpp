#include "io/frame.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mesh/geometry.hpp"

namespace invasim {

int MeshFrame::n_bodies() const {
  int n = 0;
  for (int b : triangle_body) n = std::max(n, b + 1);
  return n;
}

bool same_box(const Box& a, const Box& b) {
  if (a.periodic() != b.periodic()) return false;
  constexpr double kUlps = 4.0 * std::numeric_limits<double>::epsilon();
  for (int k = 0; k < 3; ++k) {
    const double scale = std::max({std::abs(a.lo()[k]), std::abs(a.hi()[k]), std::abs(b.lo()[k]),
                                   std::abs(b.hi()[k]), a.length(k), b.length(k)});
    const double tol = kUlps * scale;
    if (!(std::abs(a.lo()[k] - b.lo()[k]) <= tol) || !(std::abs(a.hi()[k] - b.hi()[k]) <= tol))
      return false;
  }
  return true;
}

void shift_into_box(const Box& box, std::vector<Vec3>& points) {
  if (points.empty()) return;
  const Vec3 c = vertex_centroid(int(points.size()), points.data());
  Vec3 shift = Vec3::Zero();
  for (int a = 0; a < 3; ++a)
    if (box.periodic(a))
      shift[a] = -box.length(a) * std::floor((c[a] - box.lo()[a]) / box.length(a));
  for (Vec3& p : points) p += shift;
}

Frame frame_from_system(const System& sys, bool ids) {
  Frame f;
  f.box = sys.box();
  f.step = sys.step;
  f.time = sys.time;
  const Sites& s = sys.sites();
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.kind[i] == SiteKind::kCancer) {
      f.cells.pos.push_back(s.pos[i]);
      f.cells.vel.push_back(s.vel[i]);
      f.cells.orient.push_back(s.orient[i]);
      f.cells.radius.push_back(0.5 * s.diameter[i]);
      if (ids) f.cells.id.push_back(sys.site_ids()[i]);
    }
  std::vector<Vec3> x;
  for (std::size_t b = 0; b < sys.bodies().size(); ++b) {
    const MeshBody& body = sys.bodies()[b];
    const MeshTopology& topo = *body.topology;
    x.resize(body.n_vertices());
    sys.body_vertices(int(b), x.data());
    const double shape = shape_parameter(mesh_area(topo, x.data()), mesh_volume(topo, x.data()));
    shift_into_box(sys.box(), x);
    const int first = int(f.meshes.points.size());
    f.meshes.points.insert(f.meshes.points.end(), x.begin(), x.end());
    for (int v = 0; v < body.n_vertices(); ++v)
      f.meshes.point_radius.push_back(0.5 * s.diameter[body.first_site + v]);
    for (const auto& face : topo.faces()) {
      f.meshes.triangles.push_back({first + face[0], first + face[1], first + face[2]});
      f.meshes.triangle_body.push_back(int(b));
      f.meshes.triangle_shape.push_back(shape);
    }
  }
  return f;
}

}  // namespace invasim
