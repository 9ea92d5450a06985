// The one mesh-plane slicer (mesh/plane_cut) and its documented rule for a vertex exactly on
// the plane (it counts as on the normal's positive side), checked directly and through both
// of its users: the slice picture (io/slice, cut_frame) and the slice shape statistics
// (measure/slices, slice_mesh).
#include <catch2/catch.hpp>
#include <cmath>

#include "io/frame.hpp"
#include "io/slice.hpp"
#include "measure/slices.hpp"
#include "mesh/geometry.hpp"
#include "mesh/plane_cut.hpp"
#include "test_support.hpp"

using namespace invasim;

namespace {

double polygon_area(const std::vector<Point2>& p) {
  double a = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Point2 &q = p[i], &r = p[(i + 1) % p.size()];
    a += q[0] * r[1] - r[0] * q[1];
  }
  return 0.5 * std::abs(a);
}

double polygon_perimeter(const std::vector<Point2>& p) {
  double l = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Point2 &q = p[i], &r = p[(i + 1) % p.size()];
    l += std::hypot(r[0] - q[0], r[1] - q[1]);
  }
  return l;
}

}  // namespace

TEST_CASE("slicer: a vertex on the plane counts as on the normal's positive side", "[slices]") {
  const MeshShape c = test::unit_cube_mesh();
  const std::span<const std::array<int, 3>> tris = c.topology->faces();
  // x + y = 1 contains the vertical edges at (1, 0) and (0, 1): the sqrt(2) x 1 rectangle
  // through them (with collinear corners where face diagonals cross), for either normal.
  for (double sign : {1.0, -1.0}) {
    const Plane diagonal{Vec3(0.5, 0.5, 0.5), sign * Vec3(1, 1, 0).normalized()};
    const auto loops = cut_by_plane(c.vertices.data(), tris, diagonal);
    REQUIRE(loops.size() == 1);
    CHECK(loops[0].closed);
    const auto& pts = loops[0].points;
    for (std::size_t k = 0; k < pts.size(); ++k) CHECK(pts[k] != pts[(k + 1) % pts.size()]);
    for (const Vec3& corner : {Vec3(1, 0, 0), Vec3(1, 0, 1), Vec3(0, 1, 0), Vec3(0, 1, 1)})
      CHECK(std::count(pts.begin(), pts.end(), corner) == 1);
    const auto p = slice_mesh(*c.topology, c.vertices.data(), diagonal);
    REQUIRE(p.size() == 1);
    CHECK(p[0].area == Approx(std::sqrt(2.0)).epsilon(1e-14));
    CHECK(p[0].perimeter == Approx(2.0 * (1.0 + std::sqrt(2.0))).epsilon(1e-14));
  }
  // The top face in the plane z = 1: with the normal +z its vertices count as inside the
  // cube's side of the plane moved down (the section is the face); with -z the plane moved
  // up misses the cube.
  const auto top = slice_mesh(*c.topology, c.vertices.data(), Plane{Vec3(0, 0, 1), Vec3(0, 0, 1)});
  REQUIRE(top.size() == 1);
  CHECK(top[0].area == Approx(1.0).epsilon(1e-14));
  CHECK(top[0].perimeter == Approx(4.0).epsilon(1e-14));
  CHECK(slice_mesh(*c.topology, c.vertices.data(), Plane{Vec3(0, 0, 1), Vec3(0, 0, -1)}).empty());
  // Touching a single vertex (only that vertex on the positive side): nothing.
  CHECK(cut_by_plane(c.vertices.data(), tris, Plane{Vec3(1, 1, 1), Vec3(1, 1, 1).normalized()})
            .empty());
}

TEST_CASE("slicer: the slice picture and the slice statistics cut through vertices alike",
          "[slices]") {
  // One adipocyte (an icosphere of radius 2 about (7, 5, 5)) in a box periodic in y and z.
  System sys(Box(Vec3::Zero(), Vec3(12.0, 10.0, 10.0), {false, true, true}), 1);
  sys.add_mesh_scaled(icosphere(1), Vec3(7.0, 5.0, 5.0), 2.0, 2.0, 1.1);
  const Frame f = frame_from_system(sys);
  const MeshTopology& topo = *sys.bodies()[0].topology;
  const Vec3* x = f.meshes.points.data();  // body 0: the frame's first points, topology order
  int tested = 0;
  for (int v = 0; v < topo.n_vertices(); ++v) {
    const double z = x[v][2];
    if (std::abs(z - 5.0) > 1.9) continue;  // planes through vertices away from the poles
    INFO("plane z = " << z << " through vertex " << v);
    // The picture: one closed polygon without repeated points.
    const Slice s = cut_frame(f, {2, z});
    REQUIRE(s.polygons.size() == 1);
    const SlicePolygon& poly = s.polygons[0];
    CHECK(poly.closed);
    for (std::size_t k = 0; k < poly.points.size(); ++k)
      CHECK(poly.points[k] != poly.points[(k + 1) % poly.points.size()]);
    // The statistics: one profile, the same polygon.
    const auto profiles = slice_mesh(topo, x, Plane{Vec3(0, 0, z), Vec3(0, 0, 1)});
    REQUIRE(profiles.size() == 1);
    CHECK(profiles[0].corners == int(poly.points.size()));
    CHECK(profiles[0].area == Approx(polygon_area(poly.points)).epsilon(1e-12));
    CHECK(profiles[0].perimeter == Approx(polygon_perimeter(poly.points)).epsilon(1e-12));
    // Both are the limit of the cuts just below the vertex.
    const Slice below = cut_frame(f, {2, z - 1e-9});
    REQUIRE(below.polygons.size() == 1);
    CHECK(polygon_area(below.polygons[0].points) == Approx(profiles[0].area).epsilon(1e-6));
    ++tested;
  }
  CHECK(tested >= 20);
}
