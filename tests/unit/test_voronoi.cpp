// Voronoi tessellation and measurements: exact lattice cells, the two-species
// interface, closure of every random cell, invariances of A_t, the adaptive image margin,
// local adipocyte packing fractions and the radical variant.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>

#include "core/errors.hpp"
#include "measure/recycling_allocator.hpp"
#include "measure/voronoi.hpp"
#include "test_support.hpp"

using namespace invasim;

namespace {

// A walled (x), periodic (y, z) box whose lower corner is not the origin.
Box walled_box(const Vec3& lo, const Vec3& len) {
  return Box(lo, lo + len, {false, true, true});
}

// Points of a simple cubic lattice of spacing a filling the box, planes at a/2 from the walls.
std::vector<Vec3> lattice(const Vec3& lo, int nx, int ny, int nz, double a) {
  std::vector<Vec3> p;
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j)
      for (int k = 0; k < nz; ++k) p.push_back(lo + a * Vec3(i + 0.5, j + 0.5, k + 0.5));
  return p;
}

// Random points (uniform) in a box.
std::vector<Vec3> random_points(const Box& box, int n, std::uint64_t seed) {
  std::vector<Vec3> p;
  for (int i = 0; i < n; ++i)
    p.push_back(box.lo() + Vec3(test::uniform(seed, i, 0), test::uniform(seed, i, 1),
                                test::uniform(seed, i, 2))
                               .cwiseProduct(box.lengths()));
  return p;
}

// Per-site volume recomputed from the face list alone (pyramids on each face with the apex at
// the site, height |offset| / 2): equals the tessellation's volumes only if every face of
// every cell is listed exactly once.
std::vector<double> volumes_from_faces(const VoronoiTessellation& t, std::size_t n) {
  std::vector<double> v(n, 0.0);
  for (const VoronoiFace& f : t.faces) {
    const double pyramid = f.area * f.offset.norm() / 6.0;
    v[f.a] += pyramid;
    if (f.b >= 0) v[f.b] += pyramid;
  }
  return v;
}

// Sum over each cell of (face area x outward unit normal): zero for a closed polyhedron.
std::vector<Vec3> closure(const VoronoiTessellation& t, std::size_t n) {
  std::vector<Vec3> s(n, Vec3::Zero());
  for (const VoronoiFace& f : t.faces) {
    const Vec3 na = f.area * f.offset.normalized();
    s[f.a] += na;
    if (f.b >= 0) s[f.b] -= na;
  }
  return s;
}

double sum(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return s;
}

double wall_area(const VoronoiTessellation& t, int wall) {
  double s = 0.0;
  for (const VoronoiFace& f : t.faces)
    if (f.b == wall) s += f.area;
  return s;
}

// Closed surface of an axis-aligned unit cube, outward-oriented; vertex v = i + 2 j + 4 k sits
// at (i, j, k).
std::shared_ptr<const MeshTopology> cube_topology() {
  return std::make_shared<const MeshTopology>(8, std::vector<MeshTopology::Face>{{0, 4, 6},
                                                                                 {0, 6, 2},
                                                                                 {1, 3, 7},
                                                                                 {1, 7, 5},
                                                                                 {0, 1, 5},
                                                                                 {0, 5, 4},
                                                                                 {2, 6, 7},
                                                                                 {2, 7, 3},
                                                                                 {0, 2, 3},
                                                                                 {0, 3, 1},
                                                                                 {4, 5, 7},
                                                                                 {4, 7, 6}});
}

// Lattice of spacing a in a walled box (nx x n x n sites, n even): the left n_cancer x-layers
// are cancer cells, the rest are the vertices of cube-shaped "adipocytes" of 2 x 2 x 2
// lattice sites (nx - n_cancer even). Body b gets outer_volume (b + 1) a^3.
System two_species(int nx, int n, int n_cancer, double a, const Vec3& lo) {
  System sys(walled_box(lo, a * Vec3(nx, n, n)), 1);
  for (const Vec3& r : lattice(lo, n_cancer, n, n, a)) sys.add_sphere(r, 1.0);
  auto topo = cube_topology();
  for (int i = n_cancer; i < nx; i += 2)
    for (int j = 0; j < n; j += 2)
      for (int k = 0; k < n; k += 2) {
        std::vector<Vec3> x;
        for (int v = 0; v < 8; ++v)
          x.push_back(lo + a * Vec3(i + v % 2 + 0.5, j + v / 2 % 2 + 0.5, k + v / 4 + 0.5));
        const int b = sys.add_mesh(topo, x, 1.0, std::vector<double>(12, 1.0), 1.0);
        sys.bodies()[b].outer_volume = (b + 1) * a * a * a;
      }
  return sys;
}

// The same system with bodies and cells added in reverse order (a relabelling of all sites).
System reversed(const System& sys) {
  System out(sys.box(), sys.seed());
  const auto& bodies = sys.bodies();
  for (int b = int(bodies.size()) - 1; b >= 0; --b) {
    std::vector<Vec3> x(bodies[b].n_vertices());
    sys.body_vertices(b, x.data());
    out.add_mesh(bodies[b].topology, x, 2.0, bodies[b].ref_area, bodies[b].ref_volume);
    out.bodies().back().outer_volume = bodies[b].outer_volume;
  }
  const std::vector<int> cells = sys.sites_of_kind(SiteKind::kCancer);
  for (auto it = cells.rbegin(); it != cells.rend(); ++it)
    out.add_sphere(sys.sites().pos[*it], sys.sites().diameter[*it]);
  return out;
}

// Copy of sys with every site moved by d (y and z only) and wrapped.
System shifted(System sys, const Vec3& d) {
  for (Vec3& r : sys.sites().pos) r += d;
  sys.wrap_all();
  return sys;
}

}  // namespace

TEST_CASE("a simple cubic lattice gives cubic cells: volumes a^3, every face a^2") {
  const double a = 1.3;
  const Vec3 lo(-2.0, 1.0, -3.5);
  // Thin periodic directions (1 or 2 sites) exercise faces between a site and its own image.
  for (const Vec3i& n : {Vec3i(4, 3, 5), Vec3i(3, 1, 2), Vec3i(1, 1, 1)}) {
    INFO("lattice " << n.transpose());
    const Box box = walled_box(lo, a * n.cast<double>());
    const auto pts = lattice(lo, n.x(), n.y(), n.z(), a);
    const VoronoiTessellation t = tessellate(box, pts);
    REQUIRE(t.volume.size() == pts.size());
    for (double v : t.volume) CHECK(v == Approx(a * a * a).epsilon(1e-12));
    // x faces between layers, one +y and one +z face per site, two walls.
    const int n_sites = n.prod();
    CHECK(int(t.faces.size()) == (n.x() - 1) * n.y() * n.z() + 2 * n_sites + 2 * n.y() * n.z());
    int on_walls = 0;
    for (const VoronoiFace& f : t.faces) {
      CHECK(f.area == Approx(a * a).epsilon(1e-12));
      CHECK(f.offset.norm() == Approx(a).epsilon(1e-9));
      if (f.b < 0) ++on_walls;
      if (f.b >= 0) CHECK(f.a <= f.b);
    }
    CHECK(on_walls == 2 * n.y() * n.z());
  }
}

TEST_CASE("a cancer slab against an adipocyte slab: A_t, S_i, A_t^max and local phi_a exactly") {
  const double a = 1.3;
  System sys = two_species(6, 4, 2, a, Vec3(0.5, -1.0, 2.0));
  REQUIRE(sys.bodies().size() == 8);
  const double wall = 16.0 * a * a;  // L_y L_z
  const VoronoiMeasurement m = measure_voronoi(sys);
  CHECK(m.cancer_adipocyte_area == Approx(wall).epsilon(1e-12));
  CHECK(m.cancer_wall_area == Approx(wall).epsilon(1e-12));
  CHECK(m.interface_area == Approx(2.0 * wall).epsilon(1e-12));
  // Each body is a 2a cube of cells whose six sides face other bodies, cells or a wall. Bodies
  // 0-3 (layers 2-3) face cells and bodies on all six sides; bodies 4-5 (layers 4-5) have one
  // side on the right wall, which is not part of S_i.
  for (std::size_t b = 0; b < 8; ++b) {
    INFO("body " << b);
    CHECK(m.adipocyte_surface[b] == Approx((b < 4 ? 24.0 : 20.0) * a * a).epsilon(1e-12));
    CHECK(m.adipocyte_wall_area[b] == Approx(b < 4 ? 0.0 : 4.0 * a * a).margin(1e-12));
  }
  CHECK(m.adipocyte_wall_total == Approx(wall).epsilon(1e-12));
  CHECK(m.max_interface_area == Approx(2.0 * wall + (4 * 24.0 + 4 * 20.0) * a * a).epsilon(1e-12));
  CHECK(m.interface_ratio == Approx(32.0 / 208.0).epsilon(1e-12));
  // Local phi_a = V_i / (8 a^3) with V_i = (b + 1) a^3: (b + 1) / 8.
  for (std::size_t b = 0; b < 8; ++b) {
    CHECK(m.adipocyte_volume[b] == Approx(8.0 * a * a * a).epsilon(1e-12));
    CHECK(m.local_phi_a[b] == Approx((b + 1) / 8.0).epsilon(1e-12));
  }
  CHECK(m.mean_local_phi_a == Approx(4.5 / 8.0).epsilon(1e-12));
  CHECK(m.std_local_phi_a == Approx(std::sqrt(63.0 / 12.0) / 8.0).epsilon(1e-12));

  SECTION("a body without V_i has NaN phi and is left out of the statistics") {
    sys.bodies()[7].outer_volume = 0.0;
    const VoronoiMeasurement u = measure_voronoi(sys);
    CHECK(std::isnan(u.local_phi_a[7]));
    CHECK(u.mean_local_phi_a == Approx(4.0 / 8.0).epsilon(1e-12));
    CHECK(u.std_local_phi_a == Approx(2.0 / 8.0).epsilon(1e-12));
  }
  SECTION("cancer cells on both sides touch both walls") {
    // Cancer layers 0-1, bodies in layers 2-3, cancer again in layers 4-5.
    System wide(walled_box(Vec3::Zero(), a * Vec3(6, 4, 4)), 1);
    for (const Vec3& r : lattice(Vec3::Zero(), 2, 4, 4, a)) wide.add_sphere(r, 1.0);
    for (const Vec3& r : lattice(Vec3(4.0 * a, 0.0, 0.0), 2, 4, 4, a)) wide.add_sphere(r, 1.0);
    auto topo = cube_topology();
    for (int j = 0; j < 4; j += 2)
      for (int k = 0; k < 4; k += 2) {
        std::vector<Vec3> x;
        for (int v = 0; v < 8; ++v)
          x.push_back(a * Vec3(2 + v % 2 + 0.5, j + v / 2 % 2 + 0.5, k + v / 4 + 0.5));
        wide.add_mesh(topo, x, 1.0, std::vector<double>(12, 1.0), 1.0);
      }
    const VoronoiMeasurement w = measure_voronoi(wide);
    CHECK(w.cancer_wall_area == Approx(2.0 * wall).epsilon(1e-12));
    CHECK(w.cancer_adipocyte_area == Approx(2.0 * wall).epsilon(1e-12));
    for (double s : w.adipocyte_surface) CHECK(s == Approx(24.0 * a * a).epsilon(1e-12));
    CHECK(w.adipocyte_wall_total == 0.0);
    CHECK(w.max_interface_area == Approx(2.0 * wall + 4 * 24.0 * a * a).epsilon(1e-12));
    CHECK(std::isnan(w.mean_local_phi_a));
  }
}

TEST_CASE("an adipocyte on a wall: its wall faces count in neither S_i nor A_t^max") {
  // A 4 x 4 x 4 simple cubic lattice of spacing a: one cube "adipocyte" of 2 x 2 x 2 sites
  // against the left (layers 0-1) or the right wall (layers 2-3), cancer cells elsewhere.
  // Every cell is a cube of side a, so the union of the adipocyte's cells is a 2a cube: one
  // side (4 a^2) on the wall, five sides (20 a^2) against cancer cells.
  const double a = 1.3;
  const Vec3 lo(-0.7, 2.0, 5.0);
  for (int first_layer : {0, 2}) {
    INFO("adipocyte in layers " << first_layer << "-" << first_layer + 1);
    System sys(walled_box(lo, a * Vec3(4, 4, 4)), 1);
    for (const Vec3& r : lattice(lo, 4, 4, 4, a)) {
      const int layer = int(std::floor((r.x() - lo.x()) / a));
      const bool in_body = layer >= first_layer && layer < first_layer + 2 &&
                           r.y() - lo.y() < 2.0 * a && r.z() - lo.z() < 2.0 * a;
      if (!in_body) sys.add_sphere(r, 1.0);
    }
    std::vector<Vec3> x;
    for (int v = 0; v < 8; ++v)
      x.push_back(lo + a * Vec3(first_layer + v % 2 + 0.5, v / 2 % 2 + 0.5, v / 4 + 0.5));
    sys.add_mesh(cube_topology(), x, 1.0, std::vector<double>(12, 1.0), 1.0);
    REQUIRE(sys.sites().pos.size() == 64);
    const double a2 = a * a, wall = 16.0 * a2;  // wall = L_y L_z
    const VoronoiMeasurement m = measure_voronoi(sys);
    REQUIRE(m.adipocyte_surface.size() == 1);
    CHECK(m.adipocyte_surface[0] == Approx(20.0 * a2).epsilon(1e-12));
    CHECK(m.adipocyte_wall_area[0] == Approx(4.0 * a2).epsilon(1e-12));
    CHECK(m.adipocyte_wall_total == Approx(4.0 * a2).epsilon(1e-12));
    CHECK(m.cancer_adipocyte_area == Approx(20.0 * a2).epsilon(1e-12));
    CHECK(m.cancer_wall_area == Approx(2.0 * wall - 4.0 * a2).epsilon(1e-12));
    CHECK(m.interface_area == Approx(48.0 * a2).epsilon(1e-12));
    // 2 L_y L_z + S = 32 a^2 + 20 a^2 (counting the wall side too would give 56 a^2).
    CHECK(m.max_interface_area == Approx(52.0 * a2).epsilon(1e-12));
    CHECK(m.interface_ratio == Approx(48.0 / 52.0).epsilon(1e-12));
  }
}

TEST_CASE("walls by clipping: faces cut obliquely by a wall, and a face wholly beyond it") {
  // Two sites in a box 3 x 2 x 1 (walls in x), both at the same z, so that every cell is a
  // prism of height 1 over the 2D Voronoi cell in x-y (periodic in y): A at (0.25, 0) and B at
  // (0.75, 1) from the lower corner. A's cell is the triangle with corners (0, -+0.75) on the
  // left wall and (1.5, 0): the face with B (x / 2 + y = 0.75) and with B's image at y = -1
  // are cut by the wall, and A's face with its own image at y = +-2 lies beyond the wall
  // (x < -0.5) and so is empty. B's cell is the rest of the strip.
  const Vec3 lo(-1.0, 2.0, 3.0);
  const Box box = walled_box(lo, Vec3(3.0, 2.0, 1.0));
  const std::vector<Vec3> pts = {lo + Vec3(0.25, 0.5, 0.5), lo + Vec3(0.75, 1.5, 0.5)};
  const VoronoiTessellation t = tessellate(box, pts);
  CHECK(t.volume[0] == Approx(1.125).epsilon(1e-12));
  CHECK(t.volume[1] == Approx(4.875).epsilon(1e-12));
  std::map<std::pair<int, int>, std::vector<double>> faces;
  for (const VoronoiFace& f : t.faces) faces[{f.a, f.b}].push_back(f.area);
  for (auto& [key, areas] : faces) std::sort(areas.begin(), areas.end());
  const double ab = 0.75 * std::sqrt(5.0);
  CHECK(faces.size() == 6);
  REQUIRE(faces[{0, kLeftWall}].size() == 1);
  CHECK(faces[{0, kLeftWall}][0] == Approx(1.5).epsilon(1e-12));
  REQUIRE(faces[{1, kLeftWall}].size() == 1);
  CHECK(faces[{1, kLeftWall}][0] == Approx(0.5).epsilon(1e-12));
  REQUIRE(faces[{1, kRightWall}].size() == 1);
  CHECK(faces[{1, kRightWall}][0] == Approx(2.0).epsilon(1e-12));
  REQUIRE(faces[{0, 1}].size() == 2);  // with B and with B's image at y - 2
  CHECK(faces[{0, 1}][0] == Approx(ab).epsilon(1e-12));
  CHECK(faces[{0, 1}][1] == Approx(ab).epsilon(1e-12));
  // Each site with its own image in z (the prism's base); in y only B (x > 1.5 at y = 0).
  REQUIRE(faces[{0, 0}].size() == 1);
  CHECK(faces[{0, 0}][0] == Approx(1.125).epsilon(1e-12));
  REQUIRE(faces[{1, 1}].size() == 2);
  CHECK(faces[{1, 1}][0] == Approx(1.5).epsilon(1e-12));
  CHECK(faces[{1, 1}][1] == Approx(4.875).epsilon(1e-12));
}

TEST_CASE("walls by clipping equal the mirror construction") {
  // The cells of sites in a walled box are their cells among the sites and their mirror
  // images across the left wall, in a box twice as long: the face between a site and its
  // mirror image is its left wall face, faces with the other mirror images are empty.
  const Vec3 lo(1.0, -2.0, 0.5), len(4.0, 3.5, 3.0);
  const Box box = walled_box(lo, len);
  const Box twice = walled_box(lo - Vec3(len.x(), 0.0, 0.0), Vec3(2.0 * len.x(), len.y(), len.z()));
  for (std::uint64_t seed : {3, 4, 5}) {
    INFO("seed " << seed);
    std::vector<Vec3> pts = random_points(box, 60, seed);
    // Some sites close to the left wall. (Not closer: a site and its mirror image 2 d apart
    // make thin tetrahedra whose circumcentres lose precision as 1 / d, in the mirror
    // construction only; "sites at or beyond a wall are clamped to it" and the comparison
    // with voro++, tests/measure, cover those.)
    for (int i = 0; i < 6; ++i) pts[i].x() = lo.x() + 1e-3 + 0.01 * i;
    const std::size_t n = pts.size();
    std::vector<Vec3> mirrored = pts;
    for (const Vec3& p : pts) mirrored.push_back(Vec3(2.0 * lo.x() - p.x(), p.y(), p.z()));
    const VoronoiTessellation t = tessellate(box, pts);
    const VoronoiTessellation m = tessellate(twice, mirrored);
    std::vector<double> left(n, 0.0), right_t(n, 0.0), right_m(n, 0.0), to_mirror(n, 0.0);
    for (const VoronoiFace& f : t.faces) {
      if (f.b == kLeftWall) left[f.a] += f.area;
      if (f.b == kRightWall) right_t[f.a] += f.area;
    }
    double other_mirrors = 0.0;
    for (const VoronoiFace& f : m.faces) {
      if (f.b == kRightWall && f.a < int(n)) right_m[f.a] += f.area;
      if (f.b < 0 || f.a >= int(n) || f.b < int(n)) continue;
      if (f.b == f.a + int(n))
        to_mirror[f.a] += f.area;
      else
        other_mirrors += f.area;
    }
    CHECK(other_mirrors < 1e-12);
    for (std::size_t i = 0; i < n; ++i) {
      CHECK(t.volume[i] == Approx(m.volume[i]).epsilon(1e-9));
      CHECK(left[i] == Approx(to_mirror[i]).epsilon(1e-9).margin(1e-12));
      CHECK(right_t[i] == Approx(right_m[i]).epsilon(1e-9).margin(1e-12));
    }
    CHECK(sum(left) == Approx(box.wall_area()).epsilon(1e-12));
  }
}

TEST_CASE("S_i and the adipocytes' wall area recounted from the face list of a random packing") {
  // Independent bookkeeping: from tessellate()'s faces, the surface of each body's union of
  // vertex cells split into wall and non-wall parts; A_t <= A_t^max always.
  System sys = test::mixed_system(3, 150, 5.0, 0.4, 31);
  // Push the first body against the left wall so that it surely has wall faces.
  const Sites& sites = sys.sites();
  double x_min = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < sites.pos.size(); ++i)
    if (sites.body[i] == 0) x_min = std::min(x_min, sites.pos[i].x());
  for (std::size_t i = 0; i < sites.pos.size(); ++i)
    if (sites.body[i] == 0) sys.sites().pos[i].x() -= x_min - sys.box().lo().x() - 0.05;
  const VoronoiMeasurement m = measure_voronoi(sys);
  const std::size_t nb = sys.bodies().size();
  std::vector<double> surface(nb, 0.0), on_wall(nb, 0.0);
  for (const VoronoiFace& f : m.tessellation.faces) {
    const int ba = sites.body[f.a];
    if (f.b < 0) {
      if (ba >= 0) on_wall[ba] += f.area;
      continue;
    }
    const int bb = sites.body[f.b];
    if (ba >= 0 && ba != bb) surface[ba] += f.area;
    if (bb >= 0 && bb != ba) surface[bb] += f.area;
  }
  REQUIRE(on_wall[0] > 0.0);
  double total = 2.0 * sys.box().wall_area(), wall_total = 0.0;
  for (std::size_t b = 0; b < nb; ++b) {
    CHECK(m.adipocyte_surface[b] == Approx(surface[b]).epsilon(1e-12));
    CHECK(m.adipocyte_wall_area[b] == Approx(on_wall[b]).epsilon(1e-12).margin(1e-12));
    total += surface[b];
    wall_total += on_wall[b];
  }
  CHECK(m.adipocyte_wall_total == Approx(wall_total).epsilon(1e-12));
  CHECK(m.max_interface_area == Approx(total).epsilon(1e-12));
  CHECK(m.interface_area <= m.max_interface_area);
}

TEST_CASE("random points: volumes fill the box, every cell closed, every face listed once") {
  const Box box = walled_box(Vec3(3.0, -4.0, 0.25), Vec3(7.0, 5.0, 6.0));
  for (int n : {40, 400}) {
    INFO(n << " points");
    const auto pts = random_points(box, n, 17 + n);
    const VoronoiTessellation t = tessellate(box, pts);
    CHECK(sum(t.volume) == Approx(box.volume()).epsilon(1e-9));
    const std::vector<double> from_faces = volumes_from_faces(t, pts.size());
    const std::vector<Vec3> closed = closure(t, pts.size());
    double surface_sum = 0.0;
    for (const VoronoiFace& f : t.faces) surface_sum += f.area;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      CHECK(t.volume[i] > 0.0);
      CHECK(from_faces[i] == Approx(t.volume[i]).epsilon(1e-9));
      CHECK(closed[i].norm() < 1e-9 * surface_sum / n);
    }
    // The wall faces tile each wall exactly.
    CHECK(wall_area(t, kLeftWall) == Approx(box.wall_area()).epsilon(1e-9));
    CHECK(wall_area(t, kRightWall) == Approx(box.wall_area()).epsilon(1e-9));
  }
}

TEST_CASE("A_t is invariant under periodic shifts in y and z and under relabelling") {
  const System sys = test::mixed_system(2, 200, 5.0, 0.4, 23);
  const VoronoiMeasurement m = measure_voronoi(sys);
  REQUIRE(m.interface_area > 0.0);
  CHECK(m.interface_ratio > 0.0);
  CHECK(m.interface_ratio < 1.0);
  const double L = sys.box().length(1);
  for (const Vec3& d :
       {Vec3(0.0, 0.37 * L, 0.0), Vec3(0.0, 0.0, -0.61 * L), Vec3(0.0, 1.23 * L, 0.5 * L)}) {
    INFO("shift " << d.transpose());
    const VoronoiMeasurement s = measure_voronoi(shifted(sys, d));
    CHECK(s.interface_area == Approx(m.interface_area).epsilon(1e-9));
    CHECK(s.cancer_wall_area == Approx(m.cancer_wall_area).epsilon(1e-9));
    CHECK(s.max_interface_area == Approx(m.max_interface_area).epsilon(1e-9));
    for (std::size_t i = 0; i < sys.n_sites(); ++i)
      CHECK(s.tessellation.volume[i] == Approx(m.tessellation.volume[i]).epsilon(1e-9));
  }
  const System r = reversed(sys);
  const VoronoiMeasurement p = measure_voronoi(r);
  CHECK(p.interface_area == Approx(m.interface_area).epsilon(1e-9));
  CHECK(p.max_interface_area == Approx(m.max_interface_area).epsilon(1e-9));
  const std::size_t nb = sys.bodies().size();
  for (std::size_t b = 0; b < nb; ++b) {
    CHECK(p.adipocyte_surface[nb - 1 - b] == Approx(m.adipocyte_surface[b]).epsilon(1e-9));
    CHECK(p.adipocyte_volume[nb - 1 - b] == Approx(m.adipocyte_volume[b]).epsilon(1e-9));
  }
}

TEST_CASE("the adaptive margin makes sparse and dense configurations exact") {
  SECTION("one site: its cell is the whole box") {
    const Box box = walled_box(Vec3(-1.0, 2.0, 3.0), Vec3(3.0, 5.0, 7.0));
    VoronoiOptions opt;
    opt.margin = 0.01;
    const VoronoiTessellation t = tessellate(box, {Vec3(0.2, 6.5, 4.0)}, opt);
    CHECK(t.n_added > 0);  // its periodic images, found by the verification
    CHECK(t.volume[0] == Approx(105.0).epsilon(1e-12));
    std::map<int, double> by_neighbour;
    for (const VoronoiFace& f : t.faces) {
      CHECK(f.a == 0);
      // Own periodic images: one +y face (L_x L_z), one +z face (L_x L_y).
      by_neighbour[f.b] += f.area;
    }
    CHECK(t.faces.size() == 4);
    CHECK(by_neighbour[kLeftWall] == Approx(35.0).epsilon(1e-12));
    CHECK(by_neighbour[kRightWall] == Approx(35.0).epsilon(1e-12));
    CHECK(by_neighbour[0] == Approx(21.0 + 15.0).epsilon(1e-12));
  }
  SECTION("sparse and dense: a small margin gives the exact answer") {
    const Box sparse_box = walled_box(Vec3(2.0, 0.0, -5.0), Vec3(30.0, 20.0, 25.0));
    const System dense = test::mixed_system(2, 200, 5.0, 0.4, 5);
    struct Case {
      Box box;
      std::vector<Vec3> pts;
      double safe_margin;  // surely enough: the verification passes at the first build
    };
    for (const Case& c : {Case{sparse_box, random_points(sparse_box, 5, 3), 60.0},
                          Case{dense.box(), dense.sites().pos, 10.0}}) {
      INFO(c.pts.size() << " points");
      VoronoiOptions small, large;
      small.margin = 0.05;
      large.margin = c.safe_margin;
      const VoronoiTessellation s = tessellate(c.box, c.pts, small);
      const VoronoiTessellation l = tessellate(c.box, c.pts, large);
      // The small margin needed images inserted by the verification, the large one none.
      CHECK(s.n_added > 0);
      CHECK(l.n_added == 0);
      CHECK(s.n_points < l.n_points);
      CHECK(sum(s.volume) == Approx(c.box.volume()).epsilon(1e-9));
      for (std::size_t i = 0; i < c.pts.size(); ++i)
        CHECK(s.volume[i] == Approx(l.volume[i]).epsilon(1e-9));
      CHECK(s.faces.size() == l.faces.size());
    }
  }
}

TEST_CASE("sites at or beyond a wall are clamped to it, coincident sites share one cell") {
  const Box box = walled_box(Vec3::Zero(), Vec3(4.0, 3.0, 3.0));
  std::vector<Vec3> pts = random_points(box, 30, 8);
  pts[3].x() = -0.2;  // slightly beyond the left wall
  pts[4].x() = 4.0;   // exactly on the right wall
  pts[5] = pts[6];    // coincident with another site
  const VoronoiTessellation t = tessellate(box, pts);
  CHECK(sum(t.volume) == Approx(box.volume()).epsilon(1e-9));
  CHECK(t.volume[3] > 0.0);
  CHECK(t.volume[4] > 0.0);
  CHECK(t.volume[5] > 0.0);
  CHECK(t.volume[6] == 0.0);  // the higher index of a coincident pair gets no cell
  std::vector<Vec3> clamped = pts;
  clamped[3].x() = 4e-9;  // what the tessellation uses (kWallGap L_x inside the wall)
  const VoronoiTessellation c = tessellate(box, clamped);
  for (std::size_t i = 0; i < pts.size(); ++i) CHECK(c.volume[i] == Approx(t.volume[i]));
  CHECK(wall_area(t, kLeftWall) == Approx(box.wall_area()).epsilon(1e-9));
}

TEST_CASE("input errors: box without walls in x, missing weights") {
  const Box periodic(Vec3::Zero(), Vec3::Constant(3.0), {true, true, true});
  CHECK_THROWS_AS(tessellate(periodic, {Vec3(1, 1, 1)}), InputError);
  VoronoiOptions opt;
  opt.radical = true;
  CHECK_THROWS_AS(tessellate(walled_box(Vec3::Zero(), Vec3::Constant(3.0)), {Vec3(1, 1, 1)}, opt),
                  InputError);
  CHECK(tessellate(walled_box(Vec3::Zero(), Vec3::Constant(3.0)), {}).volume.empty());
}

TEST_CASE("radical variant: equal weights give the Voronoi cells, unequal ones shift the planes") {
  const Box box = walled_box(Vec3(1.0, 0.0, 0.0), Vec3(4.0, 3.0, 2.0));
  VoronoiOptions radical;
  radical.radical = true;
  SECTION("equal weights") {
    const auto pts = random_points(box, 60, 4);
    const VoronoiTessellation v = tessellate(box, pts);
    const VoronoiTessellation r = tessellate(box, pts, radical, std::vector<double>(60, 0.7));
    for (std::size_t i = 0; i < pts.size(); ++i)
      CHECK(r.volume[i] == Approx(v.volume[i]).epsilon(1e-9));
    CHECK(r.faces.size() == v.faces.size());
  }
  SECTION("alternating layers of weights 0.3 and 0.1") {
    // Layers at x = 0.5, 1.5, 2.5, 3.5 from the left wall, spacing 1: the power plane between
    // a 0.3 and a 0.1 layer is (1 + 0.3 - 0.1) / 2 = 0.6 from the 0.3 site; the wall planes
    // stay on the walls (mirror images carry the same weight).
    const auto pts = lattice(box.lo(), 4, 3, 2, 1.0);
    std::vector<double> w;
    for (const Vec3& p : pts) w.push_back(int(p.x() - box.lo().x()) % 2 == 0 ? 0.3 : 0.1);
    const VoronoiTessellation r = tessellate(box, pts, radical, w);
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const int layer = int(pts[i].x() - box.lo().x());
      const double expected[4] = {0.5 + 0.6, 0.4 + 0.4, 0.6 + 0.6, 0.4 + 0.5};
      CHECK(r.volume[i] == Approx(expected[layer]).epsilon(1e-12));
    }
    CHECK(sum(r.volume) == Approx(box.volume()).epsilon(1e-12));
  }
  SECTION("measure_voronoi uses weights (d/2)^2 when asked") {
    System sys(box, 2);
    for (const Vec3& p : lattice(box.lo(), 4, 3, 2, 1.0))
      sys.add_sphere(p, int(p.x() - box.lo().x()) % 2 == 0 ? std::sqrt(1.2) : std::sqrt(0.4));
    const VoronoiMeasurement m = measure_voronoi(sys, radical);
    CHECK(m.tessellation.volume[0] == Approx(1.1).epsilon(1e-12));
    CHECK(measure_voronoi(sys).tessellation.volume[0] == Approx(1.0).epsilon(1e-12));
  }
}

TEST_CASE("the triangulation's blocks are kept for the next call, not returned to the system") {
  // Every call builds a fresh triangulation; its freed blocks stay in the thread's pool
  // (recycling_allocator.hpp), and the next call of the same size takes them all back.
  const Box box = walled_box(Vec3(-1.0, 2.0, 0.5), Vec3(6.0, 5.0, 5.0));
  const std::vector<Vec3> p = random_points(box, 300, 11);
  const BlockPool* pool = BlockPool::of_this_thread();
  REQUIRE(pool != nullptr);
  const VoronoiTessellation first = tessellate(box, p);
  const std::size_t kept = pool->kept_bytes();
  CHECK(kept > 100000);  // a few hundred cells of ~100 bytes and their vertices
  const VoronoiTessellation second = tessellate(box, p);
  CHECK(pool->kept_bytes() == kept);
  CHECK(second.volume == first.volume);
}

TEST_CASE("interface_only: the same measurement without the faces between two cancer cells") {
  // What the main job's observer asks for (sys:voronoi): A_t, S_i, the wall areas and the
  // local packing fractions bit for bit as from the full tessellation; only the faces between
  // cancer cells (and so the cancer cells' volumes) are left out.
  const System sys = test::mixed_system(3, 150, 5.0, 0.4, 37);
  const Sites& sites = sys.sites();
  VoronoiOptions only;
  only.interface_only = true;
  const VoronoiMeasurement full = measure_voronoi(sys), part = measure_voronoi(sys, only);
  CHECK(part.interface_area == full.interface_area);
  CHECK(part.cancer_adipocyte_area == full.cancer_adipocyte_area);
  CHECK(part.cancer_wall_area == full.cancer_wall_area);
  CHECK(part.max_interface_area == full.max_interface_area);
  CHECK(part.adipocyte_surface == full.adipocyte_surface);
  CHECK(part.adipocyte_wall_area == full.adipocyte_wall_area);
  CHECK(part.adipocyte_volume == full.adipocyte_volume);
  auto same = [](double x, double y) { return x == y || (std::isnan(x) && std::isnan(y)); };
  CHECK(same(part.std_local_phi_a, full.std_local_phi_a));
  CHECK(same(part.mean_local_phi_a, full.mean_local_phi_a));
  auto cancer = [&](int i) { return i >= 0 && sites.kind[i] == SiteKind::kCancer; };
  std::size_t between_cancer = 0, kept = 0;
  for (const VoronoiFace& f : full.tessellation.faces) {
    if (cancer(f.a) && cancer(f.b))
      ++between_cancer;
    else
      ++kept;
  }
  REQUIRE(between_cancer > 100);
  CHECK(part.tessellation.faces.size() == kept);
  for (const VoronoiFace& f : part.tessellation.faces) CHECK(!(cancer(f.a) && cancer(f.b)));
  for (std::size_t i = 0; i < sites.kind.size(); ++i) {
    if (sites.kind[i] == SiteKind::kCancer)
      CHECK(std::isnan(part.tessellation.volume[i]));
    else
      CHECK(part.tessellation.volume[i] == full.tessellation.volume[i]);
  }
  // The flags of tessellate() must match the points.
  CHECK_THROWS_AS(tessellate(sys.box(), sites.pos, {}, {}, std::vector<char>(3, 1)), InputError);
}
