// Slice pictures: cells and adipocyte meshes cut by a plane (counts and geometry), periodic
// images across the plane's axis, degenerate cuts, and SVGs rendered from snapshot files.
#include <catch2/catch.hpp>

#include "../io/io_test_support.hpp"
#include "core/errors.hpp"
#include "io/atomic_file.hpp"
#include "io/frame_check.hpp"
#include "io/render_slice.hpp"
#include "io/snapshot_writer.hpp"
#include "mesh/geometry.hpp"

using namespace invasim;
using Catch::Matchers::Contains;
using iotest::TempDir;

namespace {

double polygon_area(const std::vector<Point2>& p) {
  double a = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Point2 &q = p[i], &r = p[(i + 1) % p.size()];
    a += q[0] * r[1] - r[0] * q[1];
  }
  return 0.5 * std::abs(a);
}

std::size_t occurrences(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t k = text.find(what); k != std::string::npos; k = text.find(what, k + 1)) ++n;
  return n;
}

// Box 12 x 10 x 10, walls in x. Cells of radius 0.5: three cut by z = 5 (at z = 5, 5.3, 4.8),
// two not (z = 2, 7); one adipocyte (radius 2) at z = 5 crossing the plane, one at z = 8.9
// (spanning about 6.9..10.9) that does not.
System known_configuration() {
  System sys(Box(Vec3::Zero(), Vec3(12.0, 10.0, 10.0), {false, true, true}), 1);
  for (double z : {5.0, 5.3, 4.8, 2.0, 7.0}) sys.add_sphere(Vec3(2.0, 1.0 + z, z), 1.0);
  const MeshShape shape = icosphere(1);
  sys.add_mesh_scaled(shape, Vec3(7.0, 5.0, 5.0), 2.0, 2.0, 1.1);
  sys.add_mesh_scaled(shape, Vec3(7.0, 5.0, 8.9), 2.0, 2.0, 1.1);
  return sys;
}

}  // namespace

TEST_CASE("slice plane specifications") {
  const SlicePlane p = parse_slice_plane("z=12.5");
  CHECK(p.axis == 2);
  CHECK(p.value == 12.5);
  CHECK(parse_slice_plane("x = -1").axis == 0);
  CHECK(parse_slice_plane("y=3e-1").value == 0.3);
  CHECK_THROWS_AS(parse_slice_plane("q=1"), InputError);
  CHECK_THROWS_WITH(parse_slice_plane("x=abc"),
                    "slice 'x=abc': expected x=VALUE, y=VALUE or z=VALUE");
  CHECK_THROWS_WITH(parse_slice_plane("z"), Contains("expected x=VALUE"));
}

TEST_CASE("a known configuration: 3 of 5 cells and 1 of 2 adipocytes cut by z = 5") {
  const Frame f = frame_from_system(known_configuration());
  const Slice s = cut_frame(f, {2, 5.0});
  CHECK(s.u_axis == 0);
  CHECK(s.w_axis == 1);
  const RenderCounts c = count_shapes(s);
  CHECK(c.discs == 3);
  CHECK(c.polygons == 1);
  CHECK(c.open_chains == 0);
  REQUIRE(s.discs.size() == 3);
  CHECK(s.discs[0].cell == 0);
  CHECK(s.discs[0].radius == Approx(0.5));
  CHECK(s.discs[1].radius == Approx(0.4));  // sqrt(0.5^2 - 0.3^2)
  CHECK(s.discs[2].radius == Approx(std::sqrt(0.25 - 0.04)));
  CHECK(s.discs[1].centre == Point2{2.0, 6.3});
  // The adipocyte's cross-section through its centre: a polygon inside the circle of radius 2
  // about (7, 5), with nearly the circle's area.
  const SlicePolygon& poly = s.polygons[0];
  CHECK(poly.body == 0);
  CHECK(poly.closed);
  for (const Point2& q : poly.points) CHECK(std::hypot(q[0] - 7.0, q[1] - 5.0) <= 2.0 + 1e-9);
  CHECK(polygon_area(poly.points) > 0.85 * M_PI * 4.0);
  CHECK(polygon_area(poly.points) < M_PI * 4.0);

  // Other planes: z = 9.5 cuts only the upper adipocyte; x = 2 cuts the 5 cells and nothing
  // else; a plane outside the walls is refused.
  CHECK(count_shapes(cut_frame(f, {2, 9.5})).polygons == 1);
  CHECK(count_shapes(cut_frame(f, {2, 9.5})).discs == 0);
  const RenderCounts cx = count_shapes(cut_frame(f, {0, 2.0}));
  CHECK(cx.discs == 5);
  CHECK(cx.polygons == 0);
  CHECK_THROWS_WITH(cut_frame(f, {0, 12.5}), "slice x = 12.5 lies outside the walls [0, 12]");
}

TEST_CASE("periodic images across the plane's axis are cut too") {
  System sys(Box(Vec3::Zero(), Vec3(12.0, 10.0, 10.0), {false, true, true}), 1);
  sys.add_sphere(Vec3(2.0, 5.0, 9.9), 1.0);  // its image at z = -0.1 crosses z = 0.2
  sys.add_mesh_scaled(icosphere(1), Vec3(7.0, 5.0, 9.5), 2.0, 2.0, 1.1);  // wraps in z
  const Frame f = frame_from_system(sys);
  const Slice s = cut_frame(f, {2, 0.2});
  REQUIRE(s.discs.size() == 1);
  CHECK(s.discs[0].radius == Approx(std::sqrt(0.25 - 0.09)));
  REQUIRE(s.polygons.size() == 1);
  CHECK(polygon_area(s.polygons[0].points) > 0.5);
  // The plane value is wrapped: z = 10.2 is z = 0.2.
  const Slice t = cut_frame(f, {2, 10.2});
  CHECK(t.plane.value == Approx(0.2));
  CHECK(count_shapes(t).discs == 1);
  CHECK(count_shapes(t).polygons == 1);
}

TEST_CASE("a plane within one period of a periodic box wraps, a farther one is refused") {
  System sys(Box(Vec3::Zero(), Vec3(12.0, 10.0, 10.0), {false, true, true}), 1);
  sys.add_sphere(Vec3(2.0, 5.0, 9.9), 1.0);
  const Frame f = frame_from_system(sys);
  const Slice below = cut_frame(f, {2, -9.8});  // one period below: z = 0.2
  CHECK(below.plane.value == Approx(0.2));
  CHECK(count_shapes(below).discs == 1);
  CHECK(cut_frame(f, {1, 20.0}).plane.value == 0.0);  // hi + L is lo
  // z = -1e300 wrapped would land anywhere (its digits are lost) and cut nothing.
  CHECK_THROWS_WITH(cut_frame(f, {2, -1e300}),
                    "slice z = -1e+300 lies outside the box [0, 10] by more than one period of "
                    "the periodic z axis (planes within one period are wrapped into the box)");
  CHECK_THROWS_WITH(cut_frame(f, {1, 20.5}),
                    Contains("slice y = 20.5 lies outside the box [0, 10]"));
  CHECK_THROWS_WITH(cut_frame(f, {1, -10.5}), Contains("slice y = -10.5 lies outside the box"));
}

TEST_CASE("frames with a non-finite coordinate or radius cannot be drawn") {
  CellFrame c;
  c.pos = {Vec3(1.0, 2.0, 3.0), Vec3(1.0, 2.0, 3.0)};
  c.radius = {0.5, 0.5};
  CHECK_NOTHROW(require_drawable_cells(c, "'c.xyz'", 3));
  c.pos[1][2] = NAN;
  CHECK_THROWS_WITH(require_drawable_cells(c, "'c.xyz'", 3),
                    "'c.xyz': cell 1 (line 4): position (1, 2, nan) is not finite (a picture "
                    "cannot place it)");
  c.pos[1][2] = 3.0;
  c.radius[0] = INFINITY;
  CHECK_THROWS_WITH(require_drawable_cells(c, "'s.vtp'"),
                    "'s.vtp': cell 0: radius inf is not finite (a picture cannot draw it)");
  c.radius[0] = -1.0;
  CHECK_THROWS_WITH(require_drawable_cells(c, "'s.vtp'"),
                    Contains("cell 0: radius -1 is negative"));
  MeshFrame m;
  m.points = {Vec3::Zero(), Vec3(1.0, -INFINITY, 0.0)};
  m.point_radius = {0.1, 0.1};
  CHECK_THROWS_WITH(require_drawable_meshes(m, "'a.vtp'"),
                    Contains("'a.vtp': adipocyte point 1: position (1, -inf, 0) is not finite"));
  m.points[1][1] = 0.0;
  m.point_radius[0] = NAN;
  CHECK_THROWS_WITH(require_drawable_meshes(m, "'a.vtp'"),
                    Contains("'a.vtp': adipocyte point 0: radius nan is not finite"));
}

TEST_CASE("cuts through mesh vertices are well defined") {
  const MeshShape shape = icosphere(1);
  std::vector<Vec3> x;
  for (const Vec3& v : shape.vertices) x.push_back(2.0 * v);
  const auto& faces = shape.topology->faces();
  const std::vector<std::array<int, 3>> tris(faces.begin(), faces.end());
  double top = -1e300;
  for (const Vec3& v : x) top = std::max(top, v[2]);
  // Through vertices at the same height as vertex 0 (exactly on the plane): one closed
  // polygon, no repeated points.
  for (std::size_t v = 0; v < x.size(); ++v) {
    if (std::abs(x[v][2]) > 1.9) continue;  // vertices away from the poles
    const auto polys = cut_mesh(x, tris, 2, x[v][2]);
    INFO("plane through vertex " << v);
    REQUIRE(polys.size() == 1);
    CHECK(polys[0].closed);
    for (std::size_t k = 0; k < polys[0].points.size(); ++k)
      CHECK(polys[0].points[k] != polys[0].points[(k + 1) % polys[0].points.size()]);
  }
  CHECK(cut_mesh(x, tris, 2, top).empty());  // touching the top vertex: nothing
  CHECK(cut_mesh(x, tris, 2, top + 1e-9).empty());
  CHECK(cut_mesh(x, tris, 2, 0.0).size() == 1);
  CHECK(cut_mesh(x, tris, 0, 0.3).size() == 1);
}

TEST_CASE("render from snapshot files: the same counts and the documented SVG elements") {
  TempDir dir("render");
  System sys = known_configuration();
  sys.step = 1200;
  SnapshotWriter w(dir / "snaps");
  w.write(sys);
  const auto xyz = dir / "snaps" / "cells_000001200.xyz";
  const auto vtp = dir / "snaps" / "adipocytes_000001200.vtp";
  const auto sph = dir / "snaps" / "spheres_000001200.vtp";
  for (const auto& input : {xyz, vtp, sph}) {
    INFO(input);
    const RenderCounts c = render_snapshot(input, parse_slice_plane("z=5"), dir / "s.svg");
    CHECK(c.discs == 3);
    CHECK(c.polygons == 1);
    CHECK(c.vertex_discs > 0);
  }
  const std::string svg = read_file(dir / "s.svg");
  CHECK(svg.rfind("<?xml", 0) == 0);
  CHECK(svg.find("<svg xmlns=\"http://www.w3.org/2000/svg\"") != std::string::npos);
  CHECK(occurrences(svg, "<circle data-cell=") == 3);
  // The cells in red (one kind: no orientations), and the legend's sample.
  CHECK(occurrences(svg, "fill=\"#e3221c\"") == 3 + 1);
  CHECK(occurrences(svg, "<polygon data-body=\"0\"") == 1);
  // Adipocyte 0's envelope (its mesh section and the sections of its vertex spheres within
  // one vertex radius of the plane): filled once, outlined once.
  const System sys0 = known_configuration();
  int near = 0;
  for (int v = 0; v < 42; ++v) near += std::abs(sys0.sites().pos[5 + v][2] - 5.0) < 1.0;
  CHECK(near > 0);
  CHECK(render_snapshot(vtp, parse_slice_plane("z=5"), dir / "s.svg").vertex_discs == near);
  CHECK(occurrences(svg, "<path data-body=\"0\"") == 1);
  CHECK(occurrences(svg, "<path data-outline=\"0\"") == 1);
  CHECK(occurrences(svg, "<path ") == 2);
  // Plane z: horizontal x (walls: thick), vertical y (periodic: dashed).
  CHECK(occurrences(svg, "<line data-edge=\"wall\"") == 2);
  CHECK(occurrences(svg, "<line data-edge=\"periodic\"") == 2);
  CHECK(svg.find("z = 5 \u03c3, step 1200") != std::string::npos);

  // A plane x = 7 cuts both adipocytes; the upper one crosses the periodic z edge and is drawn
  // twice (once per side); all four edges are periodic.
  const RenderCounts c = render_snapshot(vtp, parse_slice_plane("x=7"), dir / "x.svg");
  CHECK(c.polygons == 2);
  const std::string xs = read_file(dir / "x.svg");
  CHECK(occurrences(xs, "<polygon") == 3);
  CHECK(occurrences(xs, "<path data-outline=") == 3);
  CHECK(occurrences(xs, "<line data-edge=\"periodic\"") == 4);
  CHECK(occurrences(xs, "<line data-edge=\"wall\"") == 0);

  // The sample system's adipocyte 1 sticks out of the box past y = 10 and below z = 0: cut by
  // x = 7.5, it is drawn four times (itself and its images in y, z and both).
  SnapshotWriter w2(dir / "sample");
  w2.write(iotest::sample_system());
  const RenderCounts c2 = render_snapshot(dir / "sample" / "adipocytes_000001200.vtp",
                                          parse_slice_plane("x=7.5"), dir / "y.svg");
  CHECK(c2.polygons == 2);
  const std::string ys = read_file(dir / "y.svg");
  CHECK(occurrences(ys, "<polygon data-body=\"0\"") == 1);
  CHECK(occurrences(ys, "<polygon data-body=\"1\"") == 4);

  // Cells only, when the adipocyte file is missing; a missing snapshot is an IoError.
  std::filesystem::remove(vtp);
  CHECK(render_snapshot(xyz, parse_slice_plane("z=5"), dir / "c.svg").polygons == 0);
  CHECK_THROWS_WITH(render_snapshot(vtp, parse_slice_plane("z=5"), dir / "c.svg"),
                    Contains("cannot read snapshot '" + vtp.string() + "'"));
}

// The XYZ stores Origin and the Lattice length, the VTP box_lo and box_hi; with this
// box (from a pressure-wall run) lo + (hi - lo) != hi, so an exact comparison refused the frame.
TEST_CASE("render: the files of one frame agree on a box whose hi does not round-trip") {
  const double lo = -2.2306418519172917, length = 13.360457861364385;
  const double hi = 11.129816009447092;  // hi - lo == length, but lo + length != hi
  REQUIRE(hi - lo == length);
  REQUIRE(lo + length != hi);
  TempDir dir("render_box");
  System sys(Box(Vec3(lo, 0.0, 0.0), Vec3(hi, 10.0, 10.0), {false, true, true}), 1);
  sys.add_sphere(Vec3(1.0, 5.0, 5.0), 1.0);
  sys.add_mesh_scaled(icosphere(1), Vec3(6.0, 5.0, 5.0), 2.0, 2.0, 1.1);
  sys.step = 20000;
  SnapshotWriter(dir / "snaps").write(sys);
  for (const char* name :
       {"cells_000020000.xyz", "adipocytes_000020000.vtp", "spheres_000020000.vtp"}) {
    INFO(name);
    const RenderCounts c =
        render_snapshot(dir / "snaps" / name, parse_slice_plane("z=5"), dir / "s.svg");
    CHECK(c.discs == 1);
    CHECK(c.polygons == 1);
  }
  CHECK(same_box(sys.box(),
                 Box(Vec3(lo, 0.0, 0.0), Vec3(lo + length, 10.0, 10.0), {false, true, true})));

  // A real difference (1e-9 in hi.x) is still refused, naming both files and both boxes.
  System moved(Box(Vec3(lo, 0.0, 0.0), Vec3(hi + 1e-9, 10.0, 10.0), {false, true, true}), 1);
  moved.add_mesh_scaled(icosphere(1), Vec3(6.0, 5.0, 5.0), 2.0, 2.0, 1.1);
  moved.step = 20000;
  SnapshotWriter(dir / "moved").write(moved);
  std::filesystem::copy_file(dir / "snaps" / "cells_000020000.xyz",
                             dir / "moved" / "cells_000020000.xyz",
                             std::filesystem::copy_options::overwrite_existing);
  CHECK_THROWS_WITH(render_snapshot(dir / "moved" / "cells_000020000.xyz", parse_slice_plane("z=5"),
                                    dir / "m.svg"),
                    Contains("adipocytes_000020000.vtp': its box lo (-2.2306418519172917, 0, 0) hi "
                             "(11.129816010447092, 10, 10) differs from the box") &&
                        Contains("cells_000020000.xyz' beyond round-off"));
  CHECK_FALSE(same_box(sys.box(), moved.box()));
  CHECK_FALSE(same_box(sys.box(), Box(sys.box().lo(), sys.box().hi(), {true, true, true})));
}

namespace {

// The `d` attributes of the SVG's elements that start with `element` (e.g. `<path
// data-outline="0"`).
std::vector<std::string> path_data_of(const std::string& svg, const std::string& element) {
  std::vector<std::string> out;
  for (std::size_t k = svg.find(element); k != std::string::npos; k = svg.find(element, k + 1)) {
    const std::size_t d = svg.find(" d=\"", k) + 4;
    out.push_back(svg.substr(d, svg.find('"', d) - d));
  }
  return out;
}

}  // namespace

// Where the envelopes (mesh plus vertex spheres) of two adipocytes touch or overlap, the
// picture used to fill their vertex-sphere sections without outline, merging them into one
// shapeless blob: each body now has its own closed outline.
TEST_CASE("render: two adipocytes in contact are two closed outlines, not one blob") {
  // Side by side in x (mesh gap 0.5, vertex spheres overlapping), cut through their centres;
  // stacked in z, cut by a plane between them (through their vertex spheres only).
  struct Pair {
    Vec3 a, b;
    SlicePlane plane;
  };
  for (const Pair& pair : {Pair{Vec3(4.0, 5.0, 6.0), Vec3(8.5, 5.0, 6.0), {2, 6.0}},
                           Pair{Vec3(6.0, 5.0, 3.0), Vec3(6.0, 5.0, 7.5), {2, 5.25}}}) {
    INFO("z = " << pair.plane.value);
    System sys(Box(Vec3::Zero(), Vec3(12.0, 10.0, 12.0), {false, true, true}), 1);
    sys.add_mesh_scaled(icosphere(1), pair.a, 2.0, 2.0, 1.1);
    sys.add_mesh_scaled(icosphere(1), pair.b, 2.0, 2.0, 1.1);
    const std::string svg = slice_svg(cut_frame(frame_from_system(sys), pair.plane));
    for (int b : {0, 1}) {
      INFO("body " << b);
      const auto d = path_data_of(svg, "<path data-outline=\"" + std::to_string(b) + "\"");
      REQUIRE(d.size() == 1);  // one outline per body (no periodic copy here)
      CHECK(d[0].rfind("M ", 0) == 0);
      CHECK(occurrences(d[0], "M ") == occurrences(d[0], " Z"));  // every loop closed
      CHECK(d[0].substr(d[0].size() - 2) == " Z");
      CHECK(occurrences(d[0], " A ") >= 6);  // the vertex spheres' arcs
    }
    CHECK(occurrences(svg, "<path data-outline=") == 2);
    CHECK(occurrences(svg, "<circle data-vertex=") == 0);  // no unoutlined sphere sections
  }
}

TEST_CASE("render: axes with ticks in sigma, the time in tau and a legend") {
  System sys = known_configuration();
  sys.step = 1200;
  sys.time = 60.000000000013;
  const std::string svg = slice_svg(cut_frame(frame_from_system(sys), {2, 5.0}));
  // Caption and title: plane and time with their units.
  CHECK(occurrences(svg, "<title>z = 5 \u03c3, step 1200, t = 60 \u03c4</title>") == 1);
  CHECK(occurrences(svg, ">z = 5 \u03c3, step 1200, t = 60 \u03c4</text>") == 1);
  CHECK(occurrences(svg, "time in tau = sqrt(m sigma^2/eps_c)") == 1);
  // x from 0 to 12: ticks every 2 sigma (7); y from 0 to 10: every 2 (6); marks and labels.
  CHECK(occurrences(svg, "<line data-tick=\"u\"") == 7);
  CHECK(occurrences(svg, "<line data-tick=\"w\"") == 6);
  CHECK(occurrences(svg, "data-tick-label=\"u\">") == 7);
  CHECK(occurrences(svg, "data-tick-label=\"w\">") == 6);
  for (const char* label : {">0</text>", ">6</text>", ">12</text>"})
    CHECK(occurrences(svg, std::string("data-tick-label=\"u\"") + label) == 1);
  CHECK(occurrences(svg, "data-tick-label=\"w\">10</text>") == 1);
  CHECK(occurrences(svg, "data-tick-label=\"w\">12</text>") == 0);
  CHECK(occurrences(svg, "data-axis=\"u\">x [\u03c3], normal to the walls</text>") == 1);
  CHECK(occurrences(svg, ">y [\u03c3], periodic</text>") == 1);
  // Legend: cells (passive: no orientation), adipocytes, mesh, wall and periodic edges.
  for (const char* kind : {"cell", "adipocyte", "mesh", "wall", "periodic"})
    CHECK(occurrences(svg, std::string("<g data-legend=\"") + kind + "\">") == 1);
  CHECK(occurrences(svg, ">cancer cell (passive)</text>") == 1);
  CHECK(occurrences(svg, ">adipocyte (mesh + vertex spheres)</text>") == 1);
  CHECK(occurrences(svg, ">periodic boundary</text>") == 1);
}

TEST_CASE("render: active and passive cells in one slice are told apart") {
  System sys(Box(Vec3::Zero(), Vec3(10.0, 10.0, 10.0), {false, true, true}), 1);
  sys.add_sphere(Vec3(2.0, 2.0, 5.0), 1.0, 1.0, Vec3(0.0, 0.0, 1.0));  // active
  sys.add_sphere(Vec3(5.0, 5.0, 5.0), 1.0);                            // passive
  const std::string svg = slice_svg(cut_frame(frame_from_system(sys), {2, 5.0}));
  CHECK(occurrences(svg, "<g data-legend=\"cell-active\">") == 1);
  CHECK(occurrences(svg, "<g data-legend=\"cell-passive\">") == 1);
  CHECK(occurrences(svg, ">active cancer cell</text>") == 1);
  CHECK(occurrences(svg, ">passive cancer cell</text>") == 1);
  CHECK(occurrences(svg, "<circle data-cell=\"0\" cx=\"") == 1);
  const std::size_t passive = svg.find("<circle data-cell=\"1\"");
  REQUIRE(passive != std::string::npos);
  CHECK(svg.substr(passive, svg.find('\n', passive) - passive).find("fill=\"#fd9a4b\"") !=
        std::string::npos);
}
