// The outline of an adipocyte's section (io/slice_outline.hpp): the boundary of the union of
// its mesh polygons and vertex discs, checked against analytic areas and a grid estimate, and
// one outline per body where the envelopes of two adipocytes overlap.
#include <catch2/catch.hpp>
#include <cmath>

#include "io/slice_outline.hpp"
#include "mesh/geometry.hpp"

using namespace invasim;

namespace {

// The signed area enclosed by a loop: the polygon of its step end points plus, for each arc,
// the circular segment between its chord and the arc (counter-clockwise arcs add).
double loop_area(const OutlineLoop& loop) {
  double a = 0.0;
  Point2 prev = loop.start;
  for (const OutlineStep& s : loop.steps) {
    a += 0.5 * (prev[0] * s.to[1] - s.to[0] * prev[1]);
    if (s.radius > 0.0) {
      const double a0 = std::atan2(prev[1] - s.centre[1], prev[0] - s.centre[0]);
      const double a1 = std::atan2(s.to[1] - s.centre[1], s.to[0] - s.centre[0]);
      double theta = a1 - a0;
      while (theta <= 0.0) theta += 2.0 * M_PI;
      if (prev == s.to) theta = 2.0 * M_PI;
      CHECK((theta > M_PI + 1e-9) == s.large_arc);
      a += 0.5 * s.radius * s.radius * (theta - std::sin(theta));
    }
    prev = s.to;
  }
  return a;
}

double total_area(const std::vector<OutlineLoop>& loops) {
  double a = 0.0;
  for (const OutlineLoop& l : loops) a += loop_area(l);
  return a;
}

void check_closed(const std::vector<OutlineLoop>& loops) {
  for (const OutlineLoop& l : loops) {
    REQUIRE_FALSE(l.steps.empty());
    CHECK(std::hypot(l.steps.back().to[0] - l.start[0], l.steps.back().to[1] - l.start[1]) < 1e-9);
  }
}

SliceDisc disc(double u, double w, double r) {
  return SliceDisc{0, {u, w}, r};
}

// The union's area on a fine grid (midpoint rule), for shapes inside [lo, hi]^2.
double grid_area(const std::vector<std::vector<Point2>>& polys, const std::vector<SliceDisc>& ds,
                 double lo, double hi, int n) {
  const double h = (hi - lo) / n;
  long inside = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double u = lo + (i + 0.5) * h, w = lo + (j + 0.5) * h;
      bool in = false;
      for (const SliceDisc& d : ds) in |= std::hypot(u - d.centre[0], w - d.centre[1]) < d.radius;
      for (const auto& p : polys) {  // even-odd
        bool odd = false;
        for (std::size_t a = 0, b = p.size() - 1; a < p.size(); b = a++)
          if ((p[a][1] > w) != (p[b][1] > w) &&
              u < p[a][0] + (w - p[a][1]) / (p[b][1] - p[a][1]) * (p[b][0] - p[a][0]))
            odd = !odd;
        in |= odd;
      }
      inside += in;
    }
  return double(inside) * h * h;
}

}  // namespace

TEST_CASE("union outline: discs alone, overlapping, disjoint and nested") {
  // One disc: a full circle.
  auto one = union_outline({}, {disc(1.0, 2.0, 0.5)});
  REQUIRE(one.size() == 1);
  check_closed(one);
  CHECK(total_area(one) == Approx(M_PI * 0.25));

  // Two overlapping unit discs at distance 1: one loop of two arcs, the area of the union.
  auto two = union_outline({}, {disc(0.0, 0.0, 1.0), disc(1.0, 0.0, 1.0)});
  REQUIRE(two.size() == 1);
  CHECK(two[0].steps.size() == 2);
  check_closed(two);
  const double lens = 2.0 * std::acos(0.5) - 0.5 * std::sqrt(3.0);  // overlap of the two
  CHECK(total_area(two) == Approx(2.0 * M_PI - lens).epsilon(1e-12));

  // Disjoint discs: one loop each; a disc inside another: nothing of its own.
  auto apart = union_outline({}, {disc(0.0, 0.0, 1.0), disc(3.0, 0.0, 1.0), disc(0.2, 0.1, 0.3)});
  CHECK(apart.size() == 2);
  check_closed(apart);
  CHECK(total_area(apart) == Approx(2.0 * M_PI));
}

TEST_CASE("union outline: a polygon with discs on its edges and inside it") {
  const std::vector<Point2> square{{0.0, 0.0}, {2.0, 0.0}, {2.0, 2.0}, {0.0, 2.0}};
  // A disc inside: the square alone (four segments).
  auto inner = union_outline({square}, {disc(1.0, 1.0, 0.5)});
  REQUIRE(inner.size() == 1);
  CHECK(inner[0].steps.size() == 4);
  CHECK(total_area(inner) == Approx(4.0));
  // A disc on a corner: the square plus three quarters of the disc.
  auto corner = union_outline({square}, {disc(2.0, 2.0, 0.5)});
  REQUIRE(corner.size() == 1);
  check_closed(corner);
  CHECK(total_area(corner) == Approx(4.0 + 0.75 * M_PI * 0.25));
  // The same square given clockwise: the same region, the same outline area.
  const std::vector<Point2> clockwise(square.rbegin(), square.rend());
  CHECK(total_area(union_outline({clockwise}, {disc(2.0, 2.0, 0.5)})) ==
        Approx(4.0 + 0.75 * M_PI * 0.25));
  // A hole (a second loop inside the first, even-odd): its edges are outline too, and a disc
  // in the hole covers part of it.
  const std::vector<Point2> hole{{0.5, 0.5}, {1.5, 0.5}, {1.5, 1.5}, {0.5, 1.5}};
  auto holed = union_outline({square, hole}, {disc(1.0, 1.0, 0.3)});
  check_closed(holed);
  CHECK(holed.size() == 3);  // outer square, hole, the disc inside the hole
  CHECK(total_area(holed) == Approx(4.0 - 1.0 + M_PI * 0.09));
}

TEST_CASE("union outline: a ring of discs on a polygon's vertices, as a mesh section") {
  // A hexagon of radius 2 with a disc of radius 0.9 on every vertex and on every edge midpoint:
  // one outer loop whose area matches a fine grid estimate.
  std::vector<Point2> hexagon;
  std::vector<SliceDisc> discs;
  for (int k = 0; k < 6; ++k) {
    const double a = k * M_PI / 3.0, b = (k + 0.5) * M_PI / 3.0;
    hexagon.push_back({2.0 * std::cos(a), 2.0 * std::sin(a)});
    discs.push_back(disc(2.0 * std::cos(a), 2.0 * std::sin(a), 0.9));
    discs.push_back(disc(std::sqrt(3.0) * std::cos(b), std::sqrt(3.0) * std::sin(b), 0.7));
  }
  const auto loops = union_outline({hexagon}, discs);
  REQUIRE(loops.size() == 1);
  check_closed(loops);
  for (const OutlineStep& s : loops[0].steps) CHECK(s.radius > 0.0);  // the discs cover it
  CHECK(total_area(loops) == Approx(grid_area({hexagon}, discs, -3.5, 3.5, 1400)).epsilon(2e-3));
}

TEST_CASE("two adipocytes stacked in z: a plane between them gives two separate outlines") {
  // Meshes of radius 2 at z = 3 and z = 7.5 (mesh gap 0.5); vertex spheres of radius 1 reach
  // 1 beyond each mesh, so the plane z = 5.25 cuts the vertex spheres of both and no mesh.
  System sys(Box(Vec3::Zero(), Vec3(12.0, 10.0, 12.0), {false, true, true}), 1);
  sys.add_mesh_scaled(icosphere(1), Vec3(6.0, 5.0, 3.0), 2.0, 2.0, 1.1);
  sys.add_mesh_scaled(icosphere(1), Vec3(6.0, 5.0, 7.5), 2.0, 2.0, 1.1);
  const Slice s = cut_frame(frame_from_system(sys), {2, 5.25});
  REQUIRE(s.polygons.empty());
  int per_body[2] = {0, 0};
  for (const SliceDisc& d : s.vertex_discs) {
    REQUIRE((d.body == 0 || d.body == 1));
    ++per_body[d.body];
  }
  CHECK(per_body[0] > 0);
  CHECK(per_body[1] > 0);
  const auto outlines = body_outlines(s);
  REQUIRE(outlines.size() == 2);
  for (const BodyOutline& b : outlines) {
    INFO("body " << b.body);
    check_closed(b.loops);
    // Every corner of the outline lies on a circle of the body's own discs.
    std::vector<SliceDisc> own;
    for (const SliceDisc& d : s.vertex_discs)
      if (d.body == b.body) own.push_back(d);
    for (const OutlineLoop& l : b.loops)
      for (const OutlineStep& step : l.steps) {
        double off = INFINITY;
        for (const SliceDisc& d : own)
          off = std::min(
              off,
              std::abs(std::hypot(step.to[0] - d.centre[0], step.to[1] - d.centre[1]) - d.radius));
        CHECK(off < 1e-9);
      }
    CHECK(total_area(b.loops) == Approx(grid_area({}, own, 0.0, 12.0, 1200)).epsilon(5e-3));
  }
}
