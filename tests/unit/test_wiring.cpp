// The run layer's object model and its rules (run/objects.hpp, run/wiring.hpp), with no Lua:
// a force joins one System, groups and methods act on their own System, the pressure wall
// finds its Walls, a Dynamics re-prepares only after a change, run_steps is the one run
// path, a restored checkpoint continues without re-preparing, and a temporary contact change
// is undone on every exit.
#include <catch2/catch.hpp>

#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>

#include "core/errors.hpp"
#include "core/progress.hpp"
#include "run/wiring.hpp"
#include "test_support.hpp"

using namespace invasim;
using Catch::Matchers::Contains;

namespace {

// A System of 20 spheres between walls with its Contacts, and the group of all its sites.
std::shared_ptr<SystemHandle> small_system(std::uint64_t seed = 3) {
  System spheres = test::random_spheres(20, 0.2, true, seed);
  auto sim = std::make_shared<SystemHandle>(spheres.box(), seed);
  sim->system = std::move(spheres);
  attach_force(sim, std::make_shared<Contacts>(std::make_shared<ContactForce>(ContactParams{})),
               "Contacts");
  return sim;
}

std::shared_ptr<Group> group_of(const std::shared_ptr<SystemHandle>& sim) {
  auto g = std::make_shared<Group>();
  g->name = "all";
  g->sites = test::all_sites(sim->system);
  g->owner = sim;
  g->epoch = sim->system.site_epoch();
  return g;
}

// A damped Dynamics moving `group`.
std::shared_ptr<DynamicsHandle> damped(const std::shared_ptr<Group>& group) {
  auto d = std::make_shared<DynamicsHandle>(0.01);
  auto m = std::make_shared<MethodHandle>();
  m->kind = "Damped";
  m->method = Method::damped(group->sites, 1.0);
  m->group = group;
  d->dynamics.add(m->method);
  d->methods.push_back(m);
  return d;
}

}  // namespace

TEST_CASE("attach_force: a force joins one System, and the System records the change", "[run]") {
  auto a = small_system(), b = small_system(4);
  auto walls = std::make_shared<Walls>(std::make_shared<WallForce>(), true, true);
  const auto before = a->revision;
  attach_force(a, walls, "Walls");
  CHECK(a->revision == before + 1);
  CHECK(a->handles.size() == 2);
  CHECK(a->forces.terms().size() == 2);
  CHECK_THROWS_WITH(attach_force(a, walls, "Walls"), Contains("already in the System"));
  CHECK_THROWS_WITH(attach_force(b, walls, "Walls"), Contains("already in another System"));
  CHECK(b->handles.size() == 1);
}

TEST_CASE("owner_of and the group checks name the call and the group", "[run]") {
  auto sim = small_system(), other = small_system(5);
  const auto group = group_of(sim);
  CHECK(&owner_of(group->owner, "Active", "hint") == sim.get());
  CHECK_THROWS_WITH(owner_of(std::weak_ptr<SystemHandle>{}, "tethers", "add them first"),
                    Contains("tethers: not in a System; add them first"));
  std::weak_ptr<SystemHandle> gone = std::make_shared<SystemHandle>(sim->system.box(), 1);
  CHECK_THROWS_WITH(owner_of(gone, "tethers", "x"), Contains("its System no longer exists"));
  CHECK_NOTHROW(require_same_system(*group, *sim, "sample"));
  CHECK_THROWS_WITH(require_same_system(*group, *other, "sample"),
                    Contains("sample: group 'all' belongs to another System"));
  CHECK_NOTHROW(require_current(*group, "run"));
  sim->system.set_site_epoch(sim->system.site_epoch() + 1);  // as after a division
  CHECK_THROWS_WITH(require_current(*group, "run"), Contains("made before cells divided"));
}

TEST_CASE("prepare_dynamics links the pressure wall to the System's one left Walls", "[run]") {
  auto sim = small_system();
  auto d = damped(group_of(sim));
  CHECK(prepare_dynamics(*d, sim, "run") == nullptr);  // no pressure wall: nothing to link
  d->dynamics.set_pressure_wall(std::make_shared<PressureWall>());
  CHECK_THROWS_WITH(prepare_dynamics(*d, sim, "run"), Contains("run: the pressure wall needs"));
  auto right_only =
      std::make_shared<Walls>(std::make_shared<WallForce>(1.0, false, true), false, true);
  attach_force(sim, right_only, "Walls");
  CHECK_THROWS_WITH(prepare_dynamics(*d, sim, "run"), Contains("its Walls have left = false"));
  attach_force(sim, std::make_shared<Walls>(std::make_shared<WallForce>(), true, true), "Walls");
  CHECK_THROWS_WITH(prepare_dynamics(*d, sim, "run"), Contains("the System has several Walls"));
  auto other = small_system(6);
  d->walls = std::make_shared<Walls>(std::make_shared<WallForce>(), true, true);
  attach_force(other, d->walls, "Walls");
  CHECK_THROWS_WITH(prepare_dynamics(*d, sim, "run"), Contains("not a force of this System"));
  CHECK_THROWS_WITH(prepare_dynamics(*d, other, "minimize"),
                    Contains("minimize: Damped: group 'all' belongs to another System"));
  d->methods.clear();
  PressureWall* wall = prepare_dynamics(*d, other, "run");
  REQUIRE(wall != nullptr);
  CHECK(wall->walls == d->walls->force);
}

TEST_CASE("run_steps: the one run path, a Dynamics re-prepares only after a change", "[run]") {
  // Two copies of one System: one run in two pieces, one in a single run_steps call.
  auto one = small_system(), two = small_system();
  auto d1 = damped(group_of(one)), d2 = damped(group_of(two));
  Simulation run1 = make_simulation(one, d1), run2 = make_simulation(two, d2);
  CHECK(run_steps(run1, one, *d1, 30, nullptr).steps == 30);
  CHECK(run_steps(run1, one, *d1, 20, nullptr).steps == 20);
  CHECK(run_steps(run2, two, *d2, 50, nullptr).steps == 50);
  CHECK(one->system.step == 50);
  for (std::size_t i = 0; i < one->system.n_sites(); ++i) {
    CHECK(one->system.sites().pos[i] == two->system.sites().pos[i]);  // bit for bit
    CHECK(one->system.sites().force[i] == two->system.sites().force[i]);
  }
  // run_steps marks the System changed and the Dynamics as having run on it at that revision.
  const auto revision = one->revision;
  run_steps(run1, one, *d1, 1, nullptr);
  CHECK(one->revision == revision + 1);
  d1->record.check(d1->dynamics, one);
  CHECK(d1->dynamics.prepared());  // unchanged since: no re-preparation
  one->changed();
  d1->record.check(d1->dynamics, one);
  CHECK_FALSE(d1->dynamics.prepared());
}

TEST_CASE("run_steps: progress hears of every chunk, and only of the run it was given to",
          "[run]") {
  auto sim = small_system();
  auto d = damped(group_of(sim));
  Simulation run = make_simulation(sim, d);
  std::ostringstream out;
  auto progress = std::make_shared<Progress>(ProgressOptions{}, out, false, [] { return 0.0; });
  run_steps(run, sim, *d, 250, progress);  // chunks of at most 100 steps
  CHECK(progress->step() == 250);
  // A run whose preparation fails leaves no progress behind for the next one.
  d->dynamics.set_pressure_wall(std::make_shared<PressureWall>());  // no Walls in the System
  CHECK_THROWS_WITH(run_steps(run, sim, *d, 10, progress), Contains("run: the pressure wall"));
  d->dynamics.set_pressure_wall(nullptr);
  run_steps(run, sim, *d, 10, nullptr);
  CHECK(sim->system.step == 260);
  CHECK(progress->step() == 250);
}

TEST_CASE("restored_from_checkpoint: the Dynamics continues without re-preparing", "[run]") {
  auto sim = small_system();
  attach_force(sim, std::make_shared<Walls>(std::make_shared<WallForce>(), true, true), "Walls");
  auto d = damped(group_of(sim));
  auto wall = std::make_shared<PressureWall>();
  d->dynamics.set_pressure_wall(wall);
  const auto revision = sim->revision;
  restored_from_checkpoint(sim, d.get());
  CHECK(sim->revision == revision + 1);
  CHECK(d->dynamics.prepared());
  CHECK(wall->walls != nullptr);  // linked to the System's Walls
  d->record.check(d->dynamics, sim);
  CHECK(d->dynamics.prepared());           // recorded as having run on this revision
  restored_from_checkpoint(sim, nullptr);  // the System alone
  CHECK(sim->revision == revision + 2);
}

TEST_CASE("TemporaryContacts: applied for its lifetime, undone on every exit", "[run]") {
  auto sim = small_system();
  auto force = only_contacts(*sim, "compress: key 'contacts'");
  ContactParams cohesive = force->params();
  cohesive.alpha = 0.2;
  cohesive.beta = 0.1;
  force->set_params(cohesive);
  ContactParams off = cohesive;
  off.beta = 0.0;
  const auto applied = sim->revision;
  try {
    const TemporaryContacts guard(*sim, force, off);
    CHECK(force->params().beta == 0.0);
    CHECK(sim->revision == applied + 1);  // a Dynamics re-prepares with the changed contacts
    throw std::runtime_error("an engine error");
  } catch (const std::runtime_error&) {
  }
  CHECK(force->params().beta == 0.1);
  CHECK(sim->revision == applied + 2);  // ... and again with its own
  ContactParams invalid = cohesive;
  invalid.beta = 0.5;  // beta must stay below alpha: refused, nothing changed
  const auto revision = sim->revision;
  CHECK_THROWS_AS(TemporaryContacts(*sim, force, invalid), InputError);
  CHECK(force->params().beta == 0.1);
  CHECK(sim->revision == revision);
  attach_force(sim, std::make_shared<Contacts>(std::make_shared<ContactForce>(ContactParams{})),
               "Contacts");
  CHECK_THROWS_WITH(only_contacts(*sim, "minimize: key 'contacts'"),
                    Contains("minimize: key 'contacts': the System has several Contacts"));
  auto bare = std::make_shared<SystemHandle>(sim->system.box(), 1);
  CHECK_THROWS_WITH(only_contacts(*bare, "compress"), Contains("has no Contacts force"));
}
