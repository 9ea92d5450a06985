// Lipolysis (integrate/lipolysis.hpp): which adipocytes a cancer cell touches (contact with a
// vertex, across the periodic edges too), how far their reference volume falls, that the
// reference shape parameter is kept, the floor, and the operation a Simulation schedules.
#include <catch2/catch.hpp>
#include <cmath>

#include "core/errors.hpp"
#include "integrate/lipolysis.hpp"
#include "mesh/geometry.hpp"
#include "mesh/topology.hpp"
#include "run/operations.hpp"
#include "run/simulation.hpp"
#include "test_support.hpp"

using namespace invasim;

namespace {

// Two adipocytes (radius 2, vertex diameter 0.5): body 0 at y = 0.3 (straddling the periodic
// y edge), body 1 far from it.
System two_bodies() {
  System sys(Box(Vec3::Zero(), Vec3(16.0, 12.0, 12.0), {false, true, true}), 1);
  const MeshShape shape = icosphere(1);
  sys.add_mesh_scaled(shape, Vec3(4.0, 0.3, 6.0), 2.0, 0.5, 1.1);
  sys.add_mesh_scaled(shape, Vec3(11.0, 6.0, 6.0), 2.0, 0.5, 1.1);
  sys.wrap_all();
  return sys;
}

double reference_area(const MeshBody& b) {
  double a = 0.0;
  for (double x : b.ref_area) a += x;
  return a;
}

// The vertex of body b with the smallest y (unwrapped).
Vec3 lowest_vertex(const System& sys, int b) {
  std::vector<Vec3> x(sys.bodies()[b].n_vertices());
  sys.body_vertices(b, x.data());
  Vec3 low = x[0];
  for (const Vec3& v : x)
    if (v.y() < low.y()) low = v;
  return low;
}

}  // namespace

TEST_CASE("lipolysis: a cell touches a body within (d_cell + d_vertex)/2 of a vertex, across y") {
  System sys = two_bodies();
  const Lipolysis lip({0.01, 0.5});
  CHECK(lip.touched(sys) == std::vector<char>{0, 0});
  // Below the lowest vertex of body 0, across the periodic y edge: contact distance 0.75.
  const Vec3 v = lowest_vertex(sys, 0);
  const double contact = 0.5 * (1.0 + 0.5);
  Vec3 r = v - Vec3(0.0, contact * 0.999, 0.0);
  Vec3 wrapped = r;
  Vec3i image = Vec3i::Zero();
  sys.box().wrap(wrapped, image);
  REQUIRE(image.y() == -1);  // the cell sits on the other side of the periodic edge
  sys.add_sphere(wrapped, 1.0);
  CHECK(lip.touched(sys) == std::vector<char>{1, 0});
  // Just beyond the contact distance: not touching.
  System far = two_bodies();
  Vec3 r2 = v - Vec3(0.0, contact * 1.001, 0.0);
  image = Vec3i::Zero();
  far.box().wrap(r2, image);
  far.add_sphere(r2, 1.0);
  CHECK(lip.touched(far) == std::vector<char>{0, 0});
}

TEST_CASE("lipolysis: v_0 falls by rate x v_0(initial) x elapsed, A_0 kept, down to the floor") {
  System sys = two_bodies();
  const Vec3 v = lowest_vertex(sys, 0);
  Vec3 r = v - Vec3(0.0, 0.5, 0.0), wrapped = r;
  Vec3i image = Vec3i::Zero();
  sys.box().wrap(wrapped, image);
  sys.add_sphere(wrapped, 1.0);
  const MeshBody b0 = sys.bodies()[0], b1 = sys.bodies()[1];
  const double shape0 = shape_parameter(reference_area(b0), b0.ref_volume);
  const Lipolysis lip({0.01, 0.5});
  CHECK(lip.apply(sys, 5.0) == 1);
  const MeshBody& a0 = sys.bodies()[0];
  CHECK(a0.ref_volume == Approx(b0.ref_volume * (1.0 - 0.05)).epsilon(1e-14));
  CHECK(a0.ref_volume_initial == b0.ref_volume);
  CHECK(shape_parameter(reference_area(a0), a0.ref_volume) == Approx(shape0).epsilon(1e-13));
  for (std::size_t k = 0; k < a0.ref_area.size(); ++k)  // every face by the same factor
    CHECK(a0.ref_area[k] / b0.ref_area[k] == Approx(std::cbrt(0.95 * 0.95)).epsilon(1e-13));
  // The untouched body is unchanged, bit for bit.
  CHECK(sys.bodies()[1].ref_volume == b1.ref_volume);
  CHECK(sys.bodies()[1].ref_area == b1.ref_area);
  // A second application subtracts the same amount (linear in time), then the floor holds.
  lip.apply(sys, 5.0);
  CHECK(sys.bodies()[0].ref_volume == Approx(b0.ref_volume * 0.9).epsilon(1e-14));
  lip.apply(sys, 1e6);
  CHECK(sys.bodies()[0].ref_volume == Approx(b0.ref_volume * 0.5).epsilon(1e-14));
  CHECK(shape_parameter(reference_area(sys.bodies()[0]), sys.bodies()[0].ref_volume) ==
        Approx(shape0).epsilon(1e-12));
  const double at_floor = sys.bodies()[0].ref_volume;
  lip.apply(sys, 10.0);
  CHECK(sys.bodies()[0].ref_volume == at_floor);
  // rate 0 changes nothing but still reports the touch.
  CHECK(Lipolysis({0.0, 0.5}).apply(sys, 10.0) == 1);
  CHECK(sys.bodies()[0].ref_volume == at_floor);
}

TEST_CASE("lipolysis: bad parameters are refused, naming the value") {
  CHECK_THROWS_WITH(Lipolysis({-1.0, 0.5}), Catch::Contains("rate = -1 must be >= 0"));
  CHECK_THROWS_WITH(Lipolysis({0.1, 0.0}), Catch::Contains("floor = 0 must be in (0, 1]"));
  CHECK_THROWS_WITH(Lipolysis({0.1, 1.5}), Catch::Contains("floor = 1.5 must be in (0, 1]"));
  System sys = two_bodies();
  CHECK_THROWS_WITH(Lipolysis({0.1, 0.5}).apply(sys, -1.0),
                    Catch::Contains("elapsed time -1 must be >= 0"));
}

TEST_CASE("lipolysis operation: every N steps, N dt of lipolysis") {
  auto sys = std::make_shared<System>(two_bodies());
  const Vec3 v = lowest_vertex(*sys, 0);
  Vec3 r = v - Vec3(0.0, 0.5, 0.0);
  Vec3i image = Vec3i::Zero();
  sys->box().wrap(r, image);
  sys->add_sphere(r, 1.0);
  const double v0 = sys->bodies()[0].ref_volume;
  auto forces = std::make_shared<ForceField>();
  auto dyn = std::make_shared<Dynamics>(0.01);
  Simulation sim(sys, forces, dyn);
  auto lip = std::make_shared<const Lipolysis>(LipolysisParams{0.01, 0.5});
  sim.add(std::make_shared<LipolysisOperation>(lip, 10, 0), Trigger::every(10));
  sim.run(30);  // no forces or methods: nothing moves; applied at steps 10, 20, 30
  CHECK(sys->bodies()[0].ref_volume == Approx(v0 * (1.0 - 3 * 0.01 * 10 * 0.01)).epsilon(1e-13));
  CHECK(sys->bodies()[1].ref_volume == sys->bodies()[1].ref_volume_initial);

  SECTION("a run starting between two multiples credits only its own steps") {
    auto late = std::make_shared<System>(*sys);
    const double start_v0 = late->bodies()[0].ref_volume;
    late->step = 35;  // a production after a quench of 35 steps
    Simulation run(late, forces, std::make_shared<Dynamics>(0.01));
    run.add(std::make_shared<LipolysisOperation>(lip, 10, 35), Trigger::every(10));
    run.run(25);  // to step 60: applied at 40 (5 steps since 35), 50 and 60: 25 steps in all
    CHECK(late->bodies()[0].ref_volume == Approx(start_v0 - 25 * 0.01 * 0.01 * v0).epsilon(1e-13));
  }
}

TEST_CASE("lipolysis: V_i follows the union volume of the shrunk body") {
  System sys = two_bodies();
  const Vec3 v = lowest_vertex(sys, 0);
  Vec3 r = v - Vec3(0.0, 0.5, 0.0);
  Vec3i image = Vec3i::Zero();
  sys.box().wrap(r, image);
  sys.add_sphere(r, 1.0);
  const MeshBody& b = sys.bodies()[0];
  std::vector<Vec3> x(b.n_vertices());
  sys.body_vertices(0, x.data());
  sys.bodies()[0].outer_volume = union_volume(*b.topology, x.data(), 0.5, 0.04);
  const double v_outer = b.outer_volume, v0 = b.ref_volume;
  Lipolysis({0.01, 0.5}).apply(sys, 20.0);  // v_0 to 0.8 of its initial value
  REQUIRE(b.ref_volume == Approx(0.8 * v0).epsilon(1e-14));
  // The body scaled about its centroid to enclose 0.8 of its mesh volume, on a grid 5x finer.
  const Vec3 c = vertex_centroid(b.n_vertices(), x.data());
  const double s = std::cbrt(0.8 * v0 / mesh_volume(*b.topology, x.data()));
  std::vector<Vec3> y(x);
  for (Vec3& p : y) p = c + s * (p - c);
  const double expected = union_volume(*b.topology, y.data(), 0.5, 0.04);
  CHECK(b.outer_volume == Approx(expected).epsilon(2e-3));
  CHECK(b.outer_volume < v_outer);
  CHECK(sys.bodies()[1].outer_volume == two_bodies().bodies()[1].outer_volume);
}
