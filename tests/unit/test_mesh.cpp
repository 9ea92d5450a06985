// Icosphere topology and mesh geometry against exact results.
#include <catch2/catch.hpp>

#include "core/errors.hpp"
#include "mesh/geometry.hpp"

using namespace invasim;
using Catch::Matchers::Contains;

TEST_CASE("icosphere(1) has 42 vertices, 80 faces, 120 edges and unit-sphere vertices") {
  const MeshShape s = icosphere(1);
  CHECK(s.topology->n_vertices() == 42);
  CHECK(s.topology->n_faces() == 80);
  CHECK(s.topology->n_edges() == 120);
  for (const Vec3& v : s.vertices) CHECK(v.norm() == Approx(1.0).epsilon(1e-14));
  const MeshShape s0 = icosphere(0);
  CHECK(s0.topology->n_vertices() == 12);
  CHECK(s0.topology->n_faces() == 20);
  CHECK(icosphere(2).topology->n_vertices() == 162);
}

TEST_CASE("icosphere is outward oriented: every face normal points away from the centre") {
  const MeshShape s = icosphere(1);
  for (const auto& f : s.topology->faces()) {
    const Vec3 &a = s.vertices[f[0]], &b = s.vertices[f[1]], &c = s.vertices[f[2]];
    CHECK((b - a).cross(c - a).dot(a + b + c) > 0.0);
  }
}

TEST_CASE("regular icosahedron: volume and area match the exact polyhedron") {
  const MeshShape s = icosphere(0);
  const double edge = (s.vertices[0] - s.vertices[11]).norm();
  const double v_exact = 5.0 / 12.0 * (3.0 + std::sqrt(5.0)) * edge * edge * edge;
  const double a_exact = 5.0 * std::sqrt(3.0) * edge * edge;
  CHECK(mesh_volume(*s.topology, s.vertices.data()) == Approx(v_exact).epsilon(1e-13));
  CHECK(mesh_area(*s.topology, s.vertices.data()) == Approx(a_exact).epsilon(1e-13));
}

TEST_CASE("icosphere(1) volume and area equal the sum over its exact faces") {
  // Every face is a flat triangle with vertices on the unit sphere: its cone to the centre
  // has volume |a.(b x c)|/6 exactly, computed independently of the mesh routines.
  const MeshShape s = icosphere(1);
  double v = 0, a = 0;
  for (const auto& f : s.topology->faces()) {
    const Vec3 &p = s.vertices[f[0]], &q = s.vertices[f[1]], &r = s.vertices[f[2]];
    v += std::abs(p.dot(q.cross(r))) / 6.0;
    a += 0.5 * (q - p).cross(r - p).norm();
  }
  CHECK(mesh_volume(*s.topology, s.vertices.data()) == Approx(v).epsilon(1e-14));
  CHECK(mesh_area(*s.topology, s.vertices.data()) == Approx(a).epsilon(1e-14));
  CHECK(v < 4.0 / 3.0 * M_PI);
  CHECK(v > 0.85 * 4.0 / 3.0 * M_PI);
}

TEST_CASE(
    "shape parameter of the icosphere is 1.0240583..., invariant under translation and scale") {
  const MeshShape s = icosphere(1);
  std::vector<Vec3> x = s.vertices;
  auto A = [&]() {
    return shape_parameter(mesh_area(*s.topology, x.data()), mesh_volume(*s.topology, x.data()));
  };
  CHECK(A() == Approx(1.0240583207).epsilon(1e-9));
  for (Vec3& v : x) v = 3.7 * v + Vec3(100.0, -50.0, 7.0);
  CHECK(A() == Approx(1.0240583207).epsilon(1e-9));
}

TEST_CASE("volume and area of a cube mesh and of a stretched icosphere") {
  std::vector<Vec3> x = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                         {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (Vec3& v : x) v *= 2.0;
  MeshTopology cube(8, {{0, 2, 1},
                        {0, 3, 2},
                        {4, 5, 6},
                        {4, 6, 7},
                        {0, 1, 5},
                        {0, 5, 4},
                        {1, 2, 6},
                        {1, 6, 5},
                        {2, 3, 7},
                        {2, 7, 6},
                        {3, 0, 4},
                        {3, 4, 7}});
  CHECK(mesh_volume(cube, x.data()) == Approx(8.0).epsilon(1e-14));
  CHECK(mesh_area(cube, x.data()) == Approx(24.0).epsilon(1e-14));
  // An affine stretch multiplies the volume by the determinant.
  const MeshShape s = icosphere(1);
  std::vector<Vec3> y = s.vertices;
  const double v0 = mesh_volume(*s.topology, y.data());
  for (Vec3& v : y) v = Vec3(2.0 * v[0], 0.5 * v[1], 3.0 * v[2]);
  CHECK(mesh_volume(*s.topology, y.data()) == Approx(3.0 * v0).epsilon(1e-13));
}

TEST_CASE("union volume of a mesh and its vertex spheres is bracketed by exact bounds") {
  // For a unit-radius icosphere with vertex spheres of diameter 2 (radius 1, centres on the
  // unit sphere) the union lies between the ball of radius 1 + (inradius distance) and the
  // ball of radius 2; the icosphere's faces are at least 0.9 from the centre.
  const MeshShape s = icosphere(1);
  const double v = union_volume(*s.topology, s.vertices.data(), 2.0, 0.04);
  CHECK(v < 4.0 / 3.0 * M_PI * 8.0);
  CHECK(v > 4.0 / 3.0 * M_PI * std::pow(1.9, 3));
  // Tiny vertex spheres: the union is the mesh volume itself (to grid resolution).
  const double vm = mesh_volume(*s.topology, s.vertices.data());
  CHECK(union_volume(*s.topology, s.vertices.data(), 1e-3, 0.01) == Approx(vm).epsilon(5e-3));
  // Non-convex: two opposite vertices pushed deep inside (vertical lines through the dents
  // cross the surface four times), and a vertex pulled far out.
  std::vector<Vec3> dented = s.vertices;
  int top = 0, bottom = 0, side = 0;
  for (int i = 0; i < int(dented.size()); ++i) {
    if (dented[i][2] > dented[top][2]) top = i;
    if (dented[i][2] < dented[bottom][2]) bottom = i;
    if (dented[i][0] > dented[side][0]) side = i;
  }
  dented[top] *= 0.2;
  dented[bottom] *= 0.3;
  dented[side] *= 1.8;
  const double vd = mesh_volume(*s.topology, dented.data());
  CHECK(std::abs(vd - vm) > 0.05 * vm);  // (the shape changed)
  CHECK(union_volume(*s.topology, dented.data(), 1e-3, 0.01) == Approx(vd).epsilon(5e-3));
}

TEST_CASE("malformed meshes are refused with a message naming the problem") {
  CHECK_THROWS_WITH(MeshTopology(4, {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {1, 3, 5}}),
                    Contains("outside [0, 4)"));
  CHECK_THROWS_WITH(MeshTopology(4, {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}}),
                    Contains("faces; a closed mesh needs >= 4"));
  CHECK_THROWS_WITH(MeshTopology(4, {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {1, 2, 3}}),
                    Contains("used twice in the same direction"));
  CHECK_THROWS_WITH(MeshTopology(5, {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 1}}),
                    Contains("not closed"));
  CHECK_THROWS_WITH(MeshTopology(5, {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {1, 3, 2}}),
                    Contains("vertex 4 is not used"));
  CHECK_THROWS_WITH(MeshTopology(4, {{0, 1, 1}, {0, 2, 3}, {0, 3, 1}, {1, 3, 2}}),
                    Contains("repeats a vertex"));
  CHECK_NOTHROW(MeshTopology(4, {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {1, 3, 2}}));
}
