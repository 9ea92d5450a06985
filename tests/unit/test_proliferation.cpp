// Proliferation and death (integrate/proliferation.hpp): a division's geometry, momentum, size
// class and orientation; removal of dead cells with the adipocytes' site blocks renumbered;
// groups that follow their cells (SiteChange::follow); contact counts against brute force;
// the run layer's operation keeps a Dynamics' methods on their cells; and the results do
// not depend on the order in which the sites were created beyond their indices.
#include <catch2/catch.hpp>
#include <cmath>

#include "checkpoint/state_checkpoint.hpp"
#include "core/errors.hpp"
#include "forces/wall_force.hpp"
#include "integrate/dynamics.hpp"
#include "integrate/proliferation.hpp"
#include "measure/time_correlator.hpp"
#include "mesh/geometry.hpp"
#include "mesh/topology.hpp"
#include "run/operations.hpp"
#include "run/simulation.hpp"

using namespace invasim;

namespace {

Box slab() {
  return Box(Vec3::Zero(), Vec3(20.0, 20.0, 20.0), {false, true, true});
}

}  // namespace

TEST_CASE("proliferation: a division keeps momentum, size, mass and orientation") {
  System sys(slab(), 7);
  sys.add_sphere(Vec3(10.0, 19.95, 5.0), 1.4, 2.0, Vec3(0.0, 0.0, 1.0));
  sys.sites().vel[0] = Vec3(0.3, -0.2, 0.1);
  sys.sites().image[0] = Vec3i(0, 2, 0);
  const Vec3 centre = sys.unwrapped(0);
  const Vec3 momentum = sys.sites().mass[0] * sys.sites().vel[0];
  sys.step = 40;
  ProliferationParams p;
  p.division_rate = 1e9;  // certain
  p.separation = 0.3;
  const SiteChange change = Proliferation(p).apply(sys, 1.0);
  REQUIRE(sys.n_sites() == 2);
  REQUIRE(change.born.size() == 1);
  CHECK(change.born[0] == std::make_pair(1, 0));
  CHECK(change.deaths == 0);
  CHECK(sys.site_epoch() == 1);
  const Sites& s = sys.sites();
  CHECK(s.diameter[1] == 1.4);
  CHECK(s.mass[1] == 2.0);
  CHECK(s.kind[1] == SiteKind::kCancer);
  CHECK(s.orient[1] == Vec3(0.0, 0.0, 1.0));
  CHECK(s.orient[0] == Vec3(0.0, 0.0, 1.0));
  CHECK(((s.mass[0] * s.vel[0] + s.mass[1] * s.vel[1]) - momentum).norm() < 1e-15);
  // Symmetric about the old centre, separation x d apart (unwrapped: across the y edge).
  const Vec3 a = sys.unwrapped(0), b = sys.unwrapped(1);
  CHECK((0.5 * (a + b) - centre).norm() < 1e-12);
  CHECK((a - b).norm() == Approx(0.3 * 1.4).epsilon(1e-12));
  for (int i = 0; i < 2; ++i) CHECK((s.pos[i][1] >= 0.0 && s.pos[i][1] < 20.0));
}

// The division axis is uniform on the sphere: the daughter (new site) sits at + the axis and
// the parent at -, so an axis drawn from one hemisphere would move every tracked parent the
// same way. 3375 divisions: the mean axis within 4 standard errors of 0 (1/sqrt(3N) each
// component), <a_k^2> within 4 standard errors of 1/3 (variance 4/45 per draw).
TEST_CASE("proliferation: division axes are isotropic, daughter and parent on either side") {
  System sys(Box(Vec3::Zero(), Vec3(60.0, 60.0, 60.0), {false, true, true}), 11);
  for (int i = 0; i < 15; ++i)
    for (int j = 0; j < 15; ++j)
      for (int k = 0; k < 15; ++k)
        sys.add_sphere(Vec3(6.0 + 3.4 * i, 2.0 + 3.9 * j, 2.0 + 3.9 * k), 1.0, 1.0,
                       Vec3(1.0, 0.0, 0.0));
  sys.step = 3;
  ProliferationParams p;
  p.division_rate = 1e9;  // every cell divides
  p.inhibition_contacts = 0;
  const SiteChange change = Proliferation(p).apply(sys, 1.0);
  const int n = 15 * 15 * 15;
  REQUIRE(int(change.born.size()) == n);
  Vec3 mean = Vec3::Zero(), square = Vec3::Zero();
  for (const auto& [daughter, parent] : change.born) {
    const Vec3 axis = (sys.unwrapped(daughter) - sys.unwrapped(parent)).normalized();
    mean += axis / n;
    square += axis.cwiseProduct(axis) / n;
  }
  for (int a = 0; a < 3; ++a) {
    CAPTURE(a, mean[a], square[a]);
    CHECK(std::abs(mean[a]) < 4.0 / std::sqrt(3.0 * n));
    CHECK(std::abs(square[a] - 1.0 / 3.0) < 4.0 * std::sqrt(4.0 / 45.0 / n));
  }
}

TEST_CASE("proliferation: dead cells leave, later sites and adipocyte blocks are renumbered") {
  System sys(slab(), 3);
  for (int i = 0; i < 6; ++i) sys.add_sphere(Vec3(2.0 + 2.0 * i, 5.0, 5.0), 1.0);
  sys.add_mesh_scaled(icosphere(1), Vec3(10.0, 12.0, 10.0), 2.0, 0.5, 1.1);
  sys.add_sphere(Vec3(3.0, 15.0, 15.0), 1.0);  // a cell after the adipocyte's block
  const int n_vertices = sys.bodies()[0].n_vertices();
  const Vec3 last = sys.sites().pos.back();
  const std::vector<int> map = sys.remove_sites({1, 4});
  CHECK(sys.n_sites() == std::size_t(7 + n_vertices - 2));
  CHECK(map[0] == 0);
  CHECK(map[1] == -1);
  CHECK(map[2] == 1);
  CHECK(map[4] == -1);
  CHECK(map[5] == 3);
  CHECK(sys.bodies()[0].first_site == 4);
  CHECK(sys.sites().body[4] == 0);
  CHECK(sys.sites().pos.back() == last);
  CHECK(sys.site_epoch() == 1);
  CHECK_THROWS_AS(sys.remove_sites({4}), InputError);  // an adipocyte vertex
  sys.validate();
}

TEST_CASE("proliferation: a group follows its cells through deaths and divisions") {
  SiteChange c;
  c.new_index = {0, -1, 1, 2, -1, 3};
  c.born = {{4, 0}, {5, 3}};  // the daughters of old sites 0 and 5 (new 0 and 3)
  c.deaths = 2;
  CHECK(c.follow({0, 1, 2}) == std::vector<int>{0, 1, 4});
  CHECK(c.follow({3, 4, 5}) == std::vector<int>{2, 3, 5});
  CHECK(c.follow({1, 4}).empty());
}

TEST_CASE("proliferation: contact counts equal the brute-force count, across the edges") {
  System sys(slab(), 5);
  sys.add_sphere(Vec3(5.0, 0.2, 5.0), 1.0);
  sys.add_sphere(Vec3(5.0, 19.5, 5.0), 1.4);  // touches the first across y
  sys.add_sphere(Vec3(5.9, 0.2, 5.0), 1.0);
  sys.add_sphere(Vec3(15.0, 10.0, 10.0), 1.0);  // alone
  sys.add_mesh_scaled(icosphere(1), Vec3(10.0, 10.0, 10.0), 2.0, 0.5, 1.1);
  for (int k = 0; k < 30; ++k) sys.add_sphere(Vec3(8.0 + 0.13 * k, 3.0 + 0.45 * k, 9.0), 1.0);
  const std::vector<int> counts = Proliferation(ProliferationParams{}).contacts(sys);
  const Sites& s = sys.sites();
  std::size_t rank = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s.kind[i] != SiteKind::kCancer) continue;
    int brute = 0;
    for (std::size_t j = 0; j < s.size(); ++j) {
      const double contact = 0.5 * (s.diameter[i] + s.diameter[j]);
      if (j != i && sys.box().minimum_image(s.pos[j] - s.pos[i]).norm() < contact) ++brute;
    }
    CHECK(counts.at(rank++) == brute);
  }
  CHECK(counts[0] == 2);
  CHECK(counts[3] == 0);
}

TEST_CASE("proliferation: contact inhibition holds back touching cells only") {
  System sys(slab(), 9);
  sys.add_sphere(Vec3(5.0, 5.0, 5.0), 1.0);
  sys.add_sphere(Vec3(5.8, 5.0, 5.0), 1.0);
  sys.add_sphere(Vec3(15.0, 15.0, 15.0), 1.0);
  ProliferationParams p;
  p.division_rate = 1e9;
  p.inhibition_contacts = 1;
  const SiteChange change = Proliferation(p).apply(sys, 1.0);
  REQUIRE(change.born.size() == 1);
  CHECK(change.born[0].second == 2);
}

TEST_CASE("proliferation: the operation keeps a Dynamics' methods on their cells") {
  auto sys = std::make_shared<System>(slab(), 11);
  for (int i = 0; i < 40; ++i) sys->add_sphere(Vec3(2.0 + 0.4 * i, 3.0 + 0.3 * i, 10.0), 1.0);
  auto ff = std::make_shared<ForceField>();
  ff->add(std::make_shared<WallForce>());
  auto dyn = std::make_shared<Dynamics>(0.05);
  std::vector<int> first, second;
  for (int i = 0; i < 40; ++i) (i % 2 ? second : first).push_back(i);
  dyn->add(Method::damped(first, 1.0));
  dyn->add(Method::langevin(second, 1.0, 1e-3));
  Simulation sim(sys, ff, dyn);
  ProliferationParams p;
  p.division_rate = 0.05;
  p.death_rate = 0.02;
  auto op = std::make_shared<ProliferationOperation>(std::make_shared<Proliferation>(p), 10, 0);
  sim.add(op, Trigger::every(10, 0));
  sim.run(2000);
  CHECK(op->births() > 20);
  CHECK(op->deaths() > 5);
  CHECK(sys->n_sites() == 40 + op->births() - op->deaths());
  // Every cell in exactly one method, each method's cells the descendants of its own.
  std::vector<int> owner(sys->n_sites(), 0);
  for (const auto& m : dyn->methods())
    for (int i : m->group()) ++owner.at(std::size_t(i));
  for (int o : owner) CHECK(o == 1);
  CHECK(std::is_sorted(dyn->methods()[0]->group().begin(), dyn->methods()[0]->group().end()));
  CHECK(dyn->methods()[0]->group_changed());
}

namespace {

// Cell `id`'s state at sample t (a smooth, distinct motion per cell).
void set_cell(System& sys, int site, int id, int t) {
  Sites& s = sys.sites();
  s.pos[site] = Vec3(20.0 + 0.1 * id * t, 10.0 + 0.05 * t * t + id, 30.0 + 0.3 * id);
  s.image[site] = Vec3i::Zero();
  s.vel[site] = Vec3(1.0 + id, 0.5 * t, 0.5);
  s.orient[site] = Vec3(std::cos(0.3 * t + id), std::sin(0.3 * t + id), 0.0);
}

}  // namespace

TEST_CASE("proliferation: a correlator's dead cells leave it, pairs average over the living") {
  const int n = 6, lags = 4, samples = 7, death = 3;  // cells 1 and 4 die before sample 3
  System sys(Box(Vec3::Zero(), Vec3(100.0, 100.0, 100.0), {false, true, true}), 1);
  for (int i = 0; i < n; ++i) sys.add_sphere(Vec3(20.0, 10.0 + i, 30.0), 1.0);
  TimeCorrelatorParams p;
  p.lags = lags;
  p.origin_every = 1;
  p.sample_interval = 1.0;
  std::vector<int> all(n);
  for (int i = 0; i < n; ++i) all[i] = i;
  TimeCorrelator c(all, p);
  std::vector<int> ids = all;  // original id of each current site
  std::unique_ptr<TimeCorrelator> restored;
  for (int t = 0; t < samples; ++t) {
    if (t == death) {
      const std::vector<int> map = sys.remove_sites({1, 4});
      c.sites_changed(map, sys.site_epoch());
      ids = {0, 2, 3, 5};
      // A checkpoint now, restored into a correlator built with the original group.
      restored = std::make_unique<TimeCorrelator>(all, p);
      restored->restore(c.state());
      CHECK(restored->group() == std::vector<int>{0, 1, 2, 3});
    }
    for (std::size_t k = 0; k < ids.size(); ++k) set_cell(sys, int(k), ids[k], t);
    sys.time = double(t);
    c.sample(sys);
    if (restored) restored->sample(sys);
  }
  // Brute force: every (t0, t) with t - t0 < lags, over the cells alive at both times.
  std::vector<double> msd(lags, 0.0), nn(lags, 0.0), vv(lags, 0.0), count(lags, 0.0);
  System probe(Box(Vec3::Zero(), Vec3(100.0, 100.0, 100.0), {false, true, true}), 1);
  probe.add_sphere(Vec3(1.0, 1.0, 1.0), 1.0);
  probe.add_sphere(Vec3(1.0, 1.0, 1.0), 1.0);
  for (int t0 = 0; t0 < samples; ++t0)
    for (int t = t0; t < samples && t - t0 < lags; ++t)
      for (int id = 0; id < n; ++id) {
        if ((id == 1 || id == 4) && t >= death) continue;
        set_cell(probe, 0, id, t0);
        set_cell(probe, 1, id, t);
        const Sites& s = probe.sites();
        msd[t - t0] += (s.pos[1] - s.pos[0]).squaredNorm();
        nn[t - t0] += s.orient[1].dot(s.orient[0]);
        vv[t - t0] += s.vel[1].dot(s.vel[0]);
        count[t - t0] += 1.0;
      }
  const CorrelationFunctions f = c.result(), g = restored->result();
  REQUIRE(f.msd.size() == std::size_t(lags));
  for (int lag = 0; lag < lags; ++lag) {
    CHECK(f.msd[lag] == Approx(msd[lag] / count[lag]).epsilon(1e-12).margin(1e-14));
    CHECK(f.nn[lag] == Approx(nn[lag] / count[lag]).epsilon(1e-12));
    CHECK(f.vv[lag] == Approx(vv[lag] / count[lag]).epsilon(1e-12));
    // The restored correlator continued to the same bits.
    CHECK(g.msd[lag] == f.msd[lag]);
    CHECK(g.vv[lag] == f.vv[lag]);
  }
  // A sample after a change it was not told of is refused.
  sys.remove_sites({0});
  sys.time = double(samples);
  CHECK_THROWS_AS(c.sample(sys), InputError);
}

TEST_CASE("proliferation: cells keep their identity through deaths, divisions and checkpoints") {
  System sys(slab(), 4);
  for (int i = 0; i < 5; ++i) sys.add_sphere(Vec3(2.0 + 3.0 * i, 5.0, 5.0), 1.0);
  CHECK(sys.site_ids() == std::vector<std::uint64_t>{0, 1, 2, 3, 4});
  sys.remove_sites({1, 3});
  const int daughter = sys.add_sphere(Vec3(3.0, 9.0, 5.0), 1.0);
  sys.set_site_epoch(sys.site_epoch() + 1);
  CHECK(daughter == 3);
  CHECK(sys.site_ids() == std::vector<std::uint64_t>{0, 2, 4, 5});
  CHECK(sys.next_site_id() == 6);
  // The identities and the epoch go through a checkpoint; a System built with the initial
  // number of cells takes them.
  CheckpointWriter w;
  write_system(w, sys);
  const CheckpointReader r = CheckpointReader::parse(w.bytes(), "test");
  const System back = read_system(r);
  CHECK(back.site_ids() == sys.site_ids());
  CHECK(back.next_site_id() == 6);
  CHECK(back.site_epoch() == sys.site_epoch());
  // Before any change no section is written: such checkpoints stay as they were.
  System fresh(slab(), 4);
  fresh.add_sphere(Vec3(2.0, 5.0, 5.0), 1.0);
  CheckpointWriter plain;
  write_system(plain, fresh);
  CHECK_FALSE(CheckpointReader::parse(plain.bytes(), "test").has("system.sites.id"));
  CHECK_THROWS_AS(sys.set_site_ids({0, 1, 2, 9}, 6), InputError);
}
