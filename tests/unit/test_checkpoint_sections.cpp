// Objects that save themselves (checkpoint/*_sections.hpp, state_checkpoint.hpp): each
// object's state written into a checkpoint and read back into an object built the same way
// writes the same bytes again, and its fields come back bit for bit; mismatched objects are
// refused with a message naming the mismatch.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>

#include "checkpoint/correlator_sections.hpp"
#include "checkpoint/dynamics_sections.hpp"
#include "checkpoint/state_checkpoint.hpp"
#include "test_support.hpp"

using namespace invasim;
using Catch::Matchers::Contains;

namespace {

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// A Dynamics with three methods (one with kT and f0 ramps, one anchored) and a pressure wall
// with a pressure ramp; sizes of groups 3, 2, 5.
std::shared_ptr<Dynamics> sample_dynamics(bool filled) {
  auto d = std::make_shared<Dynamics>(filled ? 0.0371 : 0.05);
  auto a = Method::active({0, 1, 2}, 0.2, filled ? 0.013 : 0.0, 25.0, 0.0);
  auto l = Method::langevin({3, 4}, 0.3, filled ? 1.0 / 3.0 : 0.0);
  auto m = Method::damped({5, 6, 7, 8, 9}, filled ? 0.7 : 0.2);
  if (filled) {
    a->set_f0_ramp(Ramp{0.0, 0.02, 1000, 4711});
    a->set_kT_ramp(Ramp{1e-3, 0.0, 7, std::nullopt});
    a->params().f0 = 0.0123;  // mid-ramp value, not the ramp's start
    m->set_kT_ramp(Ramp{0.1, 0.2, 3, 9});
  }
  d->add(a);
  d->add(l);
  d->add(m);
  auto wall = std::make_shared<PressureWall>();
  if (filled) {
    wall->pressure = 1.3e-3;
    wall->mass = 2.5;
    wall->kT = 1.0 / 7.0;
    wall->velocity = -1.0 / 3.0;
    wall->force = 0.017;
    wall->pressure_ramp = Ramp{1e-3, 2e-3, 500, 12};
  }
  d->set_pressure_wall(wall);
  return d;
}

std::string dynamics_bytes(const Dynamics& d) {
  CheckpointWriter w;
  write_dynamics(w, d);
  return w.bytes();
}

CheckpointReader parse(const CheckpointWriter& w) {
  return CheckpointReader::parse(w.bytes(), "test");
}

}  // namespace

TEST_CASE("Ramp sections round-trip, absent ramp included", "[checkpoint]") {
  CheckpointWriter w;
  write_ramp(w, Ramp{0.1, 1.0 / 3.0, 17, 5}, "a");
  write_ramp(w, Ramp{2.0, 1.0, 4, std::nullopt}, "b");
  write_ramp(w, std::nullopt, "c");
  const CheckpointReader r = parse(w);
  const auto a = read_ramp(r, "a"), b = read_ramp(r, "b"), c = read_ramp(r, "c");
  REQUIRE(a);
  CHECK(same_bits(a->to, 1.0 / 3.0));
  CHECK(a->steps == 17);
  CHECK(*a->start == 5);
  REQUIRE(b);
  CHECK_FALSE(b->start);
  CHECK_FALSE(c);
}

TEST_CASE("Dynamics, methods and pressure wall save themselves bit for bit", "[checkpoint]") {
  const auto original = sample_dynamics(true);
  CheckpointWriter w;
  write_dynamics(w, *original);
  // named sections, no positional arrays
  CHECK(w.has("dynamics.method1.f0_ramp.start"));
  CHECK(w.has("dynamics.method3.kT_ramp.from"));
  CHECK_FALSE(w.has("dynamics.method2.kT_ramp.from"));
  CHECK(w.has("dynamics.pressure_wall.ramp.to"));
  const CheckpointReader r = parse(w);
  const auto restored = sample_dynamics(false);
  read_dynamics(r, *restored);
  CHECK(dynamics_bytes(*restored) == dynamics_bytes(*original));
  CHECK(same_bits(restored->dt(), 0.0371));
  const Method& a = *restored->methods()[0];
  CHECK(same_bits(a.params().f0, 0.0123));
  CHECK(*a.f0_ramp()->start == 4711);
  CHECK(same_bits(restored->methods()[1]->params().kT, 1.0 / 3.0));
  CHECK(same_bits(restored->pressure_wall()->velocity, -1.0 / 3.0));
  CHECK(restored->pressure_wall()->pressure_ramp->steps == 500);

  SECTION("a Dynamics built differently is refused") {
    Dynamics fewer(0.05);
    fewer.add(Method::damped({0}, 0.2));
    CHECK_THROWS_WITH(read_dynamics(r, fewer),
                      Contains("its Dynamics has 3 methods, this one 1 (not the same protocol?)"));
    auto other = sample_dynamics(false);
    other->set_pressure_wall(nullptr);
    CHECK_THROWS_WITH(read_dynamics(r, *other), Contains("has a pressure wall, this one has none"));
    Dynamics sizes(0.05);
    sizes.add(Method::active({0, 1}, 0.2, 0.0, 25.0, 0.0));
    sizes.add(Method::langevin({3, 4}, 0.3, 0.0));
    sizes.add(Method::damped({5}, 0.2));
    sizes.set_pressure_wall(std::make_shared<PressureWall>());
    CHECK_THROWS_WITH(read_dynamics(r, sizes),
                      Contains("dynamics.method1 moves 3 sites in the checkpoint but 2 here"));
  }
}

TEST_CASE("a TimeCorrelator's accumulators save themselves bit for bit", "[checkpoint]") {
  System sys = test::random_spheres(30, 0.2, false, 11);
  auto d = Dynamics(0.05);
  d.add(Method::active(test::all_sites(sys), 0.2, 0.01, 5.0, 1e-3));
  ForceField ff;
  TimeCorrelatorParams p;
  p.lags = 6;
  p.origin_every = 2;
  p.sample_interval = 0.05 * 3;
  TimeCorrelator c(test::all_sites(sys), p);
  for (int k = 0; k < 9; ++k) {
    d.run(sys, ff, 3);
    c.sample(sys);
  }
  CheckpointWriter w;
  write_correlator(w, c);
  TimeCorrelator back(test::all_sites(sys), p);
  read_correlator(parse(w), back);
  CheckpointWriter again;
  write_correlator(again, back);
  CHECK(again.bytes() == w.bytes());
  CHECK(back.samples() == 9);
  // the restored correlator goes on like the original
  d.run(sys, ff, 3);
  c.sample(sys);
  back.sample(sys);
  CHECK(c.state().sums == back.state().sums);
  TimeCorrelator smaller(std::vector<int>{0, 1}, p);
  CHECK_THROWS(read_correlator(parse(w), smaller));
}

TEST_CASE("tethers and the System save themselves bit for bit", "[checkpoint]") {
  System sys = test::mixed_system(2, 10, 6.0, 0.2, 5);
  TetherForce t(0.04);
  t.add(sys, 0, 1, 5.0 / 3.0);
  t.add(sys, 2, 7, 4.25);
  t.add(sys, 3, 4, 2.0, Vec3i(0, 1, -1));  // not the nearest image: restored as it was
  CheckpointWriter w;
  write_system(w, sys);
  write_tethers(w, t);
  const CheckpointReader r = parse(w);
  const System back = read_system(r);
  TetherForce t2(0.0);
  read_tethers(r, back, t2);
  REQUIRE(t2.tethers().size() == 3);
  CHECK(t2.tethers()[2].periods == Vec3i(0, 1, -1));
  CheckpointWriter again;
  write_system(again, back);
  write_tethers(again, t2);
  CHECK(again.bytes() == w.bytes());
}

// A checkpoint written before tethers kept their image has no `tethers.periods`: its tethers
// take the nearest image as the bodies stand; a `periods` of the wrong length is refused.
TEST_CASE("tethers of a checkpoint without periods take the nearest image", "[checkpoint]") {
  System sys = test::mixed_system(2, 10, 6.0, 0.2, 5);
  const Vec3 raw = TetherForce::body_centres(sys)[0] - TetherForce::body_centres(sys)[7];
  CheckpointWriter w;
  w.put_f64("tethers.stiffness", 0.04);
  w.put_i32s("tethers.a", {0});
  w.put_i32s("tethers.b", {7});
  w.put_f64s("tethers.rest_length", {4.0});
  TetherForce t(0.0);
  read_tethers(parse(w), sys, t);
  REQUIRE(t.tethers().size() == 1);
  CHECK(t.tethers()[0].periods == sys.box().nearest_periods(raw));
  w.put_i32s("tethers.periods", {0, 1});
  TetherForce t2(0.0);
  CHECK_THROWS_WITH(read_tethers(parse(w), sys, t2), Contains("tether periods (3 per tether)"));
}
