// The parallel time step (docs/performance.md, "The parallel step", "Team steps and the
// barrier"): ForceField::compute runs consecutive team-capable terms, the
// zeroing and the integrator's drift and kick in shared parallel regions (every term of the full
// system is team-capable: one region per step); the results are bit-identical to the unfused
// sequence of loops and do not depend on the thread count.
#include <omp.h>
#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "core/parallel.hpp"
#include "core/rng.hpp"
#include "integrate/dynamics.hpp"
#include "integrate/engine_order.hpp"
#include "test_support.hpp"

using namespace invasim;

namespace {

// Restores the OpenMP thread count when a test ends (even by an exception).
struct ThreadGuard {
  int saved = omp_get_max_threads();
  ~ThreadGuard() { omp_set_num_threads(saved); }
};

// Where a call ran: inside a parallel region, and with how many threads.
struct Call {
  std::string who;
  bool in_parallel;
  int threads;
};

void record(std::vector<Call>& log, const std::string& who) {
  if (omp_get_thread_num() == 0)
    log.push_back({who, bool(omp_in_parallel()), omp_get_num_threads()});
}

// A term that adds `push` to every site's x force; team-capable or not.
class Probe : public Force {
 public:
  Probe(std::string name, double push, bool team, std::vector<Call>& log)
      : name_(std::move(name)), push_(push), team_(team), log_(log) {}
  std::string name() const override { return name_; }
  ForceResult add_forces(System& sys, const ForceFlags& flags) override {
    if (team_) return add_forces_in_own_region(sys, flags);
    record(log_, name_);
    for (Vec3& f : sys.sites().force) f[0] += push_;
    return {push_, Vec3::Zero()};
  }
  bool supports_team() const override { return team_; }
  ForceResult add_forces_team(System& sys, const ForceFlags&) override {
    record(log_, name_);
    auto& f = sys.sites().force;
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < f.size(); ++i) f[i][0] += push_;
    return {push_, Vec3::Zero()};
  }

 private:
  std::string name_;
  double push_;
  bool team_;
  std::vector<Call>& log_;
};

System spheres(int n) {
  System sys(Box(Vec3::Zero(), Vec3(40, 40, 40), {true, true, true}), 3);
  for (int i = 0; i < n; ++i)
    sys.add_sphere(Vec3(0.5 + i % 30, 0.5 + (i / 30) % 30, 0.5 + i / 900), 1.0);
  return sys;
}

}  // namespace

TEST_CASE("ForceField: consecutive team terms share one parallel region with the step's hooks") {
  ThreadGuard guard;
  omp_set_num_threads(2);
  std::vector<Call> log;
  ForceField ff;
  // Powers of two: the sums are exact, so the expected values are exact too.
  ff.add(std::make_shared<Probe>("A", 1.0, true, log));
  ff.add(std::make_shared<Probe>("S", 2.0, false, log));
  ff.add(std::make_shared<Probe>("B", 4.0, true, log));
  ff.add(std::make_shared<Probe>("C", 8.0, true, log));
  TeamHooks hooks;
  hooks.before = [&] { record(log, "before"); };
  hooks.after = [&] { record(log, "after"); };

  System sys = spheres(1100);  // above kParallelTeamItems: the regions get both threads
  for (Vec3& f : sys.sites().force) f = Vec3(100, 100, 100);
  const ForceResult r = ff.compute(sys, {}, nullptr, hooks);
  CHECK(r.energy == 15.0);
  for (const Vec3& f : sys.sites().force) REQUIRE(f == Vec3(15, 0, 0));  // zeroed, then summed
  // Region 1: before, zeroing, A; then S on its own; region 2: B, C, after.
  CHECK(ff.team_regions() == 2);
  const std::vector<std::string> order = {"before", "A", "S", "B", "C", "after"};
  REQUIRE(log.size() == order.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    INFO(order[k]);
    CHECK(log[k].who == order[k]);
    CHECK(log[k].in_parallel == (order[k] != "S"));
    CHECK(log[k].threads == (order[k] == "S" ? 1 : 2));
  }

  // A solo term last: the hook `after` gets a region of its own.
  log.clear();
  ForceField solo;
  solo.add(std::make_shared<Probe>("S", 2.0, false, log));
  solo.compute(sys, {}, nullptr, hooks);
  CHECK(solo.team_regions() == 2);
  REQUIRE(log.size() == 3);
  CHECK((log[0].who == "before" && log[1].who == "S" && log[2].who == "after"));
  CHECK(log[2].in_parallel);

  // Below the threshold the same structure runs on the calling thread alone.
  log.clear();
  System small = spheres(100);
  ff.compute(small, {}, nullptr, hooks);
  REQUIRE(log.size() == order.size());
  for (const Call& c : log) CHECK(c.threads == 1);
  for (const Vec3& f : small.sites().force) REQUIRE(f == Vec3(15, 0, 0));
}

namespace {

// The mixed system above the team threshold (27 adipocytes, 1000 cells: 2134 sites):
// cohesive contacts, walls, shape, heterogeneous tethers, active cells with thermal noise and
// ramps of kT and f0, damped vertices, and a pressure-controlled left wall with its own bath
// under a pressure ramp.
struct Mixed {
  explicit Mixed(System s) : sys(std::move(s)) {}
  System sys;
  ForceField ff;
  Dynamics dyn{0.05};
  std::shared_ptr<ContactForce> contacts;
  std::shared_ptr<PressureWall> wall;
  std::vector<std::shared_ptr<Method>> methods;
};

std::unique_ptr<Mixed> make_mixed() {
  auto m = std::make_unique<Mixed>(test::mixed_system(3, 1000, 7.0, 0.2, 91));
  ContactParams cp;
  cp.beta = 1e-2;
  m->contacts = std::make_shared<ContactForce>(cp);
  auto walls = std::make_shared<WallForce>();
  auto tethers = std::make_shared<TetherForce>(0.5);
  m->ff.add(walls);  // the protocols' order: walls, contacts, shape, tethers
  m->ff.add(m->contacts);
  m->ff.add(std::make_shared<ShapeForce>(100.0, 1.0));
  m->ff.add(tethers);
  tethers->connect_by_mean_degree(m->sys, 4.0);
  tethers->apply_heterogeneity(m->sys, 0.3);
  // The first 10 cells in no method: they stay put, and their forces must still be zeroed
  // at every step (the drift zeroes only its own sites').
  std::vector<int> cells = m->sys.sites_of_kind(SiteKind::kCancer);
  cells.erase(cells.begin(), cells.begin() + 10);
  auto active = Method::active(cells, 0.2, 0.1, 2.0, 1e-2);
  active->randomize_orientations(m->sys);
  active->set_kT_ramp(Ramp{1e-2, 2e-2, 100, {}});
  active->set_f0_ramp(Ramp{0.1, 0.05, 150, {}});
  m->methods = {active, Method::damped(m->sys.sites_of_kind(SiteKind::kVertex), 0.2)};
  for (const auto& method : m->methods) m->dyn.add(method);
  m->wall = std::make_shared<PressureWall>();
  m->wall->pressure = 1e-3;
  m->wall->kT = 1e-3;
  m->wall->walls = walls;
  m->wall->pressure_ramp = Ramp{1e-3, 2e-3, 120, {}};
  m->dyn.set_pressure_wall(m->wall);
  return m;
}

// One step as the separate loops of the step before its fusion (drift, piston, forces, kick,
// piston), each loop outside any region: the reference the fused step must reproduce. The
// piston's arithmetic is PressureWall's own (not a copy here: GCC contracts a copy to FMA or
// not depending on its surroundings, which made this reference differ from the step by 1 ulp
// in the piston's velocity at step 36; see integrate/pressure_wall.hpp). The System is in the
// engine layout (as in Dynamics' steps), with the groups as its slots.
void unfused_step(Mixed& m) {
  System& sys = m.sys;
  const double dt = m.dyn.dt();
  std::vector<GroupSlots> slots;
  for (const auto& method : m.methods) slots.push_back(GroupSlots::of(sys, method->group()));
  for (std::size_t k = 0; k < slots.size(); ++k) m.methods[k]->drift_team(sys, dt, slots[k]);
  PressureWall& w = *m.wall;
  w.half_kick(dt);
  w.move(sys.box(), dt);
  m.ff.compute(sys);
  ++sys.step;
  sys.time += dt;
  for (const auto& method : m.methods) method->apply_ramps(sys.step);
  w.pressure = w.pressure_ramp->value(sys.step);
  for (std::size_t k = 0; k < slots.size(); ++k)
    m.methods[k]->kick_team(sys, dt, sys.step, m.methods[k]->params(), slots[k]);
  w.update_force(sys, dt);
  w.half_kick(dt);
}

// The first difference between the states of a and b ("" if none): the field, the slot, both
// values to the last bit, and how many slots differ in that field.
std::string first_difference(const Mixed& a, const Mixed& b) {
  const Sites &s = a.sys.sites(), &t = b.sys.sites();
  char buf[256];
  auto vectors = [&](const char* name, const std::vector<Vec3>& x,
                     const std::vector<Vec3>& y) -> std::string {
    if (x.size() != y.size()) return std::string(name) + ": sizes differ";
    std::size_t first = x.size(), count = 0;
    for (std::size_t i = 0; i < x.size(); ++i)
      if (x[i] != y[i]) {
        first = std::min(first, i);
        ++count;
      }
    if (count == 0) return "";
    const Vec3 d = x[first] - y[first];
    std::snprintf(buf, sizeof buf,
                  "%s differs at %zu of %zu slots; first slot %zu (kind %d): "
                  "%a %a %a vs %a %a %a (difference %.3g %.3g %.3g)",
                  name, count, x.size(), first, int(s.kind[first]), x[first][0], x[first][1],
                  x[first][2], y[first][0], y[first][1], y[first][2], d[0], d[1], d[2]);
    return buf;
  };
  for (const std::string& d :
       {vectors("pos", s.pos, t.pos), vectors("vel", s.vel, t.vel),
        vectors("orient", s.orient, t.orient), vectors("force", s.force, t.force)})
    if (!d.empty()) return d;
  if (s.image != t.image) return "image differs";
  if (a.sys.box().lo() != b.sys.box().lo()) return "box differs";
  if (a.wall->velocity != b.wall->velocity || a.wall->force != b.wall->force) {
    std::snprintf(buf, sizeof buf, "wall differs: velocity %a vs %a, force %a vs %a",
                  a.wall->velocity, b.wall->velocity, a.wall->force, b.wall->force);
    return buf;
  }
  return "";
}

// Where two runs of the mixed system part, at 1 and at 2 threads, stepped together one step at
// a time ("" if they agree for `steps` steps): told when the test below fails.
std::string first_divergent_step(int steps) {
  omp_set_num_threads(1);
  auto one = make_mixed();
  omp_set_num_threads(2);
  auto two = make_mixed();
  two->dyn.step_threads().set_mode(StepThreads::Mode::kAll);
  for (int k = 1; k <= steps; ++k) {
    omp_set_num_threads(1);
    one->dyn.run(one->sys, one->ff, 1);
    omp_set_num_threads(2);
    two->dyn.run(two->sys, two->ff, 1);
    const std::string d = first_difference(*one, *two);
    if (!d.empty())
      return "step " + std::to_string(k) + " (list builds " +
             std::to_string(two->contacts->neighbor_list().builds()) + "): " + d;
  }
  return "";
}

}  // namespace

TEST_CASE(
    "parallel step of the full mixed system: bit-identical to the unfused loops, 1 and 2 threads") {
  ThreadGuard guard;
  const int steps = 200;
  omp_set_num_threads(1);
  auto one = make_mixed();
  REQUIRE(one->sys.n_sites() >= kParallelTeamItems);
  one->dyn.run(one->sys, one->ff, steps);

  omp_set_num_threads(2);
  auto two = make_mixed();
  two->dyn.step_threads().set_mode(StepThreads::Mode::kAll);  // every step on both threads
  two->dyn.run(two->sys, two->ff, steps);
  CHECK(two->dyn.step_threads().team_steps() == std::uint64_t(steps));
  // One region per step: drift and zeroing, walls, contacts with the list's rebuild test and
  // builds, shape, tethers and the kick (the contact term used to open its own regions: 2 team
  // regions around it).
  CHECK(two->ff.team_regions() == 1);
  // ... and the 200 steps share one region (Dynamics::run keeps the team between steps).
  CHECK(two->dyn.team_regions() == 1);
  CHECK(two->contacts->neighbor_list().builds() > 1);
  CHECK(two->sys.box().lo()[0] != 0.0);
  const std::string one_two = first_difference(*one, *two);
  CHECK(one_two == "");
  if (!one_two.empty()) {
    const std::string where = first_divergent_step(steps);
    CAPTURE(where);
    FAIL_CHECK("1 and 2 threads part (stepped together)");
  }

  auto ref = make_mixed();
  {
    const EngineLayoutScope layout(ref->sys);  // (the engine order of step 0, as Dynamics')
    REQUIRE(steps < int(ref->dyn.sort_every()));
    ref->dyn.prepare(ref->sys, ref->ff);
    for (int k = 0; k < steps; ++k) unfused_step(*ref);
  }
  CHECK(ref->sys.step == two->sys.step);
  CHECK(first_difference(*ref, *two) == "");
}

TEST_CASE("drift: a thread's share cut into runs of any length gives the same bits as one run") {
  // A thread drifts its share of a method's slots in runs of consecutive slots, and where the
  // shares are cut depends on the thread count: every cut must give a site the same bits.
  auto whole = make_mixed(), cut = make_mixed();
  for (auto* m : {whole.get(), cut.get()}) {
    Sites& s = m->sys.sites();
    for (std::size_t i = 0; i < s.size(); ++i)  // forces and velocities of every size
      for (int a = 0; a < 3; ++a) {
        s.force[i][a] = std::sin(1.7 * double(i) + a) * std::pow(10.0, double(int(i % 9) - 4));
        s.vel[i][a] = std::cos(0.3 * double(i) - a) * 1e-2;
      }
  }
  const double dt = whole->dyn.dt();
  for (std::size_t k = 0; k < whole->methods.size(); ++k) {
    const GroupSlots slots = GroupSlots::of(whole->sys, whole->methods[k]->group());
    whole->methods[k]->drift_slots(whole->sys, dt, slots.slot);
    // Runs of 1, 2, ..., 11 slots in turn, as the shares of ever more threads would be.
    std::size_t at = 0;
    for (int len = 1; at < slots.slot.size(); len = len % 11 + 1) {
      const std::size_t end = std::min(slots.slot.size(), at + std::size_t(len));
      cut->methods[k]->drift_slots(
          cut->sys, dt,
          std::vector<int>(slots.slot.begin() + long(at), slots.slot.begin() + long(end)));
      at = end;
    }
  }
  CHECK(first_difference(*whole, *cut) == "");
}

TEST_CASE("drift: a site that leaves the box is wrapped wherever it falls in a run") {
  // The drift moves whole blocks of 8 sites in vector lanes and the rest one by one; each form
  // must notice a site that left the box on a periodic axis (through either face) and wrap
  // it. 37 sites in one run (four blocks and a remainder of 5), one of them leaving.
  const double L = 10.0, dt = 0.05;
  const int n = 37;
  int case_index = 0;
  for (int leaver : {2, 9, 20, 31, 35})
    for (int axis : {1, 2})
      for (bool up : {true, false}) {
        CAPTURE(leaver, axis, up);
        System sys(test::cube(L, true), 3);  // walls in x, periodic y and z
        for (int i = 0; i < n; ++i)
          sys.add_sphere(Vec3(5.0, 5.0, 5.0) + 0.01 * double(i) * Vec3::Ones(), 1.0, 1.0);
        Sites& s = sys.sites();
        s.pos[leaver][axis] = up ? L - 1e-3 : 1e-3;
        s.vel[leaver][axis] = up ? 1.0 : -1.0;
        s.force[leaver][0] = 0.1 * double(++case_index);
        std::vector<int> slots(n);
        for (int i = 0; i < n; ++i) slots[std::size_t(i)] = i;
        std::vector<Vec3> before;
        for (int i = 0; i < n; ++i) before.push_back(sys.unwrapped(std::size_t(i)));
        Method(std::vector<int>(slots), MethodParams{}).drift_slots(sys, dt, slots);
        for (int i = 0; i < n; ++i) {
          CAPTURE(i);
          for (int a = 1; a < 3; ++a) {
            CHECK(s.pos[i][a] >= 0.0);
            CHECK(s.pos[i][a] < L);
          }
          // The unwrapped position moved by dt v: the image counts follow the wrap.
          CHECK((sys.unwrapped(std::size_t(i)) - before[std::size_t(i)] - dt * s.vel[i]).norm() <
                1e-12);
        }
      }
}

TEST_CASE(
    "ContactForce: its own region and the force field's team region give the same bits, with "
    "list rebuilds, at 1 and 2 threads, a compute without hooks is one region") {
  ThreadGuard guard;
  // Two copies of the mixed system moved alike: on one the contacts are evaluated by
  // ContactForce::add_forces (a region of its own, as outside a time step), on the other by
  // ForceField::compute (the team path: zeroing and the term in one region).
  for (int threads : {1, 2}) {
    CAPTURE(threads);
    omp_set_num_threads(threads);
    auto a = make_mixed(), b = make_mixed();
    ForceField team;
    team.add(b->contacts);
    for (int round = 0; round < 4; ++round) {
      CAPTURE(round);
      for (auto* m : {a.get(), b.get()})  // displacements beyond skin/2: the lists rebuild
        for (std::size_t i = 0; i < m->sys.n_sites(); ++i)
          m->sys.sites().pos[i][1] += 0.2 * std::sin(0.37 * double(i) + round);
      for (Vec3& f : a->sys.sites().force) f.setZero();
      const ForceResult own = a->contacts->add_forces(a->sys, {true, true});
      const ForceResult shared = team.compute(b->sys, {true, true});
      CHECK(team.team_regions() == 1);
      CHECK(own.energy == shared.energy);
      CHECK(own.virial == shared.virial);
      CHECK(a->sys.sites().force == b->sys.sites().force);
      // All four terms without hooks (FIRE, the measurements): one region too.
      b->ff.compute(b->sys);
      CHECK(b->ff.team_regions() == 1);
    }
    CHECK(a->contacts->neighbor_list().builds() == 4);
    CHECK(b->contacts->neighbor_list().builds() == 4);
  }
}

namespace {

// Feeds `n` steps of `seconds` each to a StepThreads; returns how many ran with 2 threads.
int feed(StepThreads& st, int n, double seconds) {
  int team = 0;
  for (int k = 0; k < n; ++k) {
    team += st.begin_step() == 2;
    st.end_step(seconds);
  }
  return team;
}

}  // namespace

TEST_CASE("StepThreads: each step on 1 thread or all, whichever measured faster") {
  ThreadGuard guard;
  omp_set_num_threads(2);
  // Steps of t = 2^-10 s (~1 ms; powers of two keep the sums exact): a window is the first
  // step count whose time reaches StepThreads::kWindowSeconds.
  const double t = std::ldexp(1.0, -10);
  const int window = int(std::ceil(StepThreads::kWindowSeconds / t));
  REQUIRE(window == 52);
  const int hold = int(StepThreads::kMinHold) * window;

  SECTION("the team is chosen when its window is faster, and measured again later") {
    StepThreads st;
    CHECK(feed(st, window, t) == 0);           // the 1-thread window
    CHECK(feed(st, window, t / 2) == window);  // the team's window: faster
    CHECK(feed(st, hold, t / 2) == hold);      // held
    CHECK(feed(st, window, t) == 0);           // measured again: 1 thread first
    CHECK(feed(st, window, t / 2) == window);
    CHECK(feed(st, 2 * hold, t / 2) == 2 * hold);  // the same choice: held twice as long
    CHECK(st.begin_step() == 1);
  }
  SECTION("a team slower than 1 thread (next to a busy core) is dropped within one window") {
    StepThreads st;
    CHECK(feed(st, window, t) == 0);
    // 3 t per step with 2 threads: the trial stops as soon as it has taken longer than the
    // whole 1-thread window (18 steps), not after 52.
    CHECK(feed(st, 18, 3 * t) == 18);
    CHECK(feed(st, hold, t) == 0);
  }
  SECTION("a team that becomes slow while held is measured again after one window") {
    StepThreads st;
    feed(st, window, t);
    feed(st, window, t / 2);
    CHECK(feed(st, window, 2 * t) == window);  // one slow window with the team
    CHECK(feed(st, window, t) == 0);           // measured again at once
    CHECK(feed(st, 27, 2 * t) == 27);          // the team's trial, abandoned after 27 steps
    CHECK(feed(st, hold, t) == 0);
  }
  SECTION("light steps never try the team") {
    StepThreads st;
    CHECK(feed(st, 200000, 20e-6) == 0);  // below kMinTeamStepSeconds
  }
  SECTION("Mode::kAll and a single thread: no measuring") {
    StepThreads st;
    st.set_mode(StepThreads::Mode::kAll);
    CHECK(feed(st, 1000, 20e-6) == 1000);
    omp_set_num_threads(1);
    StepThreads one;
    CHECK(feed(one, 1000, t) == 0);
    CHECK(one.begin_step() == 1);
  }
}

namespace {

// A term without forces that records the OpenMP thread count a step gives its regions.
class ThreadsSeen : public Force {
 public:
  std::string name() const override { return "threads seen"; }
  ForceResult add_forces(System&, const ForceFlags&) override {
    seen.push_back(omp_get_max_threads());
    return {};
  }
  std::vector<int> seen;
};

}  // namespace

TEST_CASE("Dynamics: a light step runs on the calling thread alone, the thread count is restored") {
  ThreadGuard guard;
  omp_set_num_threads(2);
  System sys = test::free_particles(20, 1.0, 3);
  ForceField ff;
  auto probe = std::make_shared<ThreadsSeen>();
  ff.add(probe);
  Dynamics dyn(0.05);
  dyn.add(Method::active(test::all_sites(sys), 0.2, 0.02, 25.0, 1e-3));
  // The 1-thread window is measured on steps of 20 us (fed here, not timed: a loaded machine
  // would make this tiny step's wall time anything), below StepThreads::kMinTeamStepSeconds:
  // 1 thread is chosen and held for kMinHold windows (20000 steps), longer than the run.
  const int light_window = int(std::ceil(StepThreads::kWindowSeconds / 20e-6));
  CHECK(feed(dyn.step_threads(), light_window, 20e-6) == 0);
  dyn.run(sys, ff, 3000);
  CHECK(dyn.step_threads().team_steps() == 0);
  CHECK(dyn.step_threads().serial_steps() == std::uint64_t(light_window) + 3000);
  REQUIRE(probe->seen.size() == 3001);  // prepare, then every step
  CHECK(probe->seen[0] == 2);           // (prepare is not a step)
  CHECK(std::count(probe->seen.begin() + 1, probe->seen.end(), 1) == 3000);
  CHECK(omp_get_max_threads() == 2);

  // Mode::kAll: every step with both threads.
  probe->seen.clear();
  dyn.step_threads().set_mode(StepThreads::Mode::kAll);
  dyn.run(sys, ff, 10);
  CHECK(std::count(probe->seen.begin(), probe->seen.end(), 2) == 10);
  CHECK(dyn.step_threads().team_steps() == 10);
  CHECK(omp_get_max_threads() == 2);
}

namespace {

// A team-capable term without forces whose preparation fails once, at one step (as a term
// refusing a box that became too short would), to test an error inside a run of team steps.
class FailsAtStep : public Force {
 public:
  explicit FailsAtStep(std::uint64_t step) : step_(step) {}
  std::string name() const override { return "fails at step"; }
  ForceResult add_forces(System& sys, const ForceFlags& flags) override {
    return add_forces_in_own_region(sys, flags);
  }
  bool supports_team() const override { return true; }
  void prepare_team(System& sys, const ForceFlags&) override {
    if (sys.step + 1 == step_ && !failed_) {
      failed_ = true;
      throw InputError("refused at step " + std::to_string(step_));
    }
  }
  ForceResult add_forces_team(System&, const ForceFlags&) override { return {}; }

 private:
  std::uint64_t step_;
  bool failed_ = false;
};

}  // namespace

TEST_CASE(
    "Dynamics: an error in a run of team steps leaves the shared region and the run can go on") {
  ThreadGuard guard;
  omp_set_num_threads(2);
  auto m = make_mixed();
  m->ff.add(std::make_shared<FailsAtStep>(37));
  m->dyn.step_threads().set_mode(StepThreads::Mode::kAll);
  CHECK_THROWS_WITH(m->dyn.run(m->sys, m->ff, 100), "refused at step 37");
  CHECK(m->sys.step == 36);  // the failing step did not complete (as on one thread)
  CHECK(m->dyn.team_regions() == 1);
  // The team is usable again: the next run makes its steps (37 again) in a new region.
  m->dyn.run(m->sys, m->ff, 10);
  CHECK(m->sys.step == 46);
  CHECK(m->dyn.team_regions() == 2);
}

namespace {

// Keeps a core busy while it lives, as another process would: the team's threads are then
// descheduled at random points (a thread late at a barrier is what exposes a team's threads
// getting out of step).
class BusyThread {
 public:
  BusyThread()
      : thread_([this] {
          while (!stop_.load(std::memory_order_relaxed)) {
          }
        }) {}
  ~BusyThread() {
    stop_ = true;
    thread_.join();
  }

 private:
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// Aborts the test program unless destroyed within `seconds`: threads of a team that got out of
// step wait at a barrier forever, and that must fail the test rather than stall the suite.
class Watchdog {
 public:
  explicit Watchdog(double seconds)
      : thread_([this, seconds] {
          std::unique_lock<std::mutex> lock(mutex_);
          if (!done_cv_.wait_for(lock, std::chrono::duration<double>(seconds),
                                 [this] { return done_; })) {
            std::fprintf(stderr, "watchdog: the team hung (threads out of step at a barrier)\n");
            std::abort();
          }
        }) {}
  ~Watchdog() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      done_ = true;
    }
    done_cv_.notify_one();
    thread_.join();
  }

 private:
  std::mutex mutex_;
  std::condition_variable done_cv_;
  bool done_ = false;
  std::thread thread_;
};

}  // namespace

TEST_CASE("Dynamics: runs of team steps that end by an error stay in step next to a busy core") {
  // The leader decides twice per step; with one flag for both decisions a thread woken late
  // from a barrier read the next decision and left the region alone (the leader then waited
  // forever): 14 of 30 runs of the test above hung next to a busy core.
  ThreadGuard guard;
  omp_set_num_threads(2);
  Watchdog watchdog(60.0);
  BusyThread busy;
  for (int round = 0; round < 12; ++round) {
    CAPTURE(round);
    auto m = make_mixed();
    m->ff.add(std::make_shared<FailsAtStep>(9));
    m->dyn.step_threads().set_mode(StepThreads::Mode::kAll);
    CHECK_THROWS_WITH(m->dyn.run(m->sys, m->ff, 20), "refused at step 9");
    m->dyn.run(m->sys, m->ff, 3);
    CHECK(m->sys.step == 11);
  }
}

TEST_CASE("Dynamics: a blow-up inside a run of team steps is reported as with one thread") {
  ThreadGuard guard;
  std::string message[2];
  for (int threads : {1, 2}) {
    omp_set_num_threads(threads);
    auto m = make_mixed();
    m->dyn.step_threads().set_mode(StepThreads::Mode::kAll);
    m->dyn.set_check_every(10);
    m->sys.sites().vel[1500] = Vec3(std::nan(""), 0.0, 0.0);
    try {
      m->dyn.run(m->sys, m->ff, 50);
    } catch (const SimulationError& e) {
      message[threads - 1] = e.what();
    }
    CHECK(m->sys.step == 10);  // the guard's first check
    CHECK(m->dyn.team_regions() == (threads == 2 ? 1u : 0u));
  }
  CHECK(message[0].find("blow-up at step 10:") != std::string::npos);
  CHECK(message[0] == message[1]);
}
