// The run layer (run/simulation.hpp, run/trigger.hpp): triggers, the order in which a
// Simulation calls its operations, stop handling, and that a run with operations follows
// the same trajectory as a plain Dynamics run. C++ only, no Lua.
#include <catch2/catch.hpp>

#include <cmath>
#include <csignal>
#include <functional>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "core/stop_request.hpp"
#include "integrate/dynamics.hpp"
#include "measure/kinetic.hpp"
#include "run/energies.hpp"
#include "run/operations.hpp"
#include "run/simulation.hpp"
#include "setup/masses.hpp"
#include "setup/velocities.hpp"
#include "test_support.hpp"

using namespace invasim;

namespace {

// Calls a function (an observer, as a Lua callback is); returning false ends the run.
class FunctionOperation : public Operation {
 public:
  FunctionOperation(std::string name, std::function<bool(Simulation&)> fn)
      : name_(std::move(name)), fn_(std::move(fn)) {}
  std::string name() const override { return name_; }
  void apply(Simulation& sim) override {
    if (!fn_(sim)) sim.request_stop();
  }

 private:
  std::string name_;
  std::function<bool(Simulation&)> fn_;
};

// A small damped system of spheres in a fully periodic box, ready to run.
struct Fixture {
  std::shared_ptr<System> sys;
  std::shared_ptr<ForceField> ff = std::make_shared<ForceField>();
  std::shared_ptr<Dynamics> dyn = std::make_shared<Dynamics>(0.01);
  Fixture() {
    sys = std::make_shared<System>(test::random_spheres(40, 0.3, false, 7));
    ff->add(std::make_shared<ContactForce>(ContactParams{}));
    dyn->add(Method::langevin(test::all_sites(*sys), 0.5, 0.1));
  }
  Simulation simulation() { return Simulation(sys, ff, dyn); }
};

// Records (name, step) of every call.
struct Recorder : Operation {
  Recorder(std::string n, std::vector<std::string>& log) : label(std::move(n)), calls(log) {}
  std::string name() const override { return label; }
  void apply(Simulation& sim) override {
    calls.push_back(label + "@" + std::to_string(sim.system().step));
  }
  std::string label;
  std::vector<std::string>& calls;
};

}  // namespace

TEST_CASE("Trigger: every, phase, at, combined, next_after", "[run]") {
  const Trigger e = Trigger::every(300);
  CHECK(e.due(0));
  CHECK(e.due(600));
  CHECK_FALSE(e.due(301));
  CHECK(*e.next_after(0) == 300);
  CHECK(*e.next_after(299) == 300);
  CHECK(*e.next_after(300) == 600);
  const Trigger p = Trigger::every(10, 3);
  CHECK(p.due(13));
  CHECK_FALSE(p.due(10));
  CHECK(*p.next_after(3) == 13);
  CHECK(*p.next_after(2) == 3);
  const Trigger a = Trigger::at({9, 5, 5});
  CHECK(*a.next_after(0) == 5);
  CHECK(*a.next_after(5) == 9);
  CHECK_FALSE(a.next_after(9));
  CHECK_FALSE(Trigger::at_end().next_after(0));
  const Trigger c = Trigger::every(700) | Trigger::at({100}) | Trigger::on_stop();
  CHECK(*c.next_after(0) == 100);
  CHECK(*c.next_after(100) == 700);
  CHECK(c.fires_on_stop());
  CHECK_FALSE(c.fires_at_end());
  CHECK(c.describe() == "every 700 steps or at step 100 or on stop");
  CHECK_THROWS_AS(Trigger::every(0), InputError);
  CHECK_THROWS_WITH(Trigger::every(5, 5), Catch::Contains("phase = 5 must be in [0, 5)"));
}

TEST_CASE("Simulation: operations run at their own steps, in the order added", "[run]") {
  Fixture f;
  Simulation sim = f.simulation();
  std::vector<std::string> log;
  sim.add(std::make_shared<Recorder>("b", log), Trigger::every(3));
  sim.add(std::make_shared<Recorder>("a", log), Trigger::every(2) | Trigger::at_end());
  sim.add(std::make_shared<Recorder>("s", log), Trigger::at({5}));
  sim.add(std::make_shared<Recorder>("x", log), Trigger::on_stop());
  std::vector<std::uint64_t> progress;
  sim.set_progress([&](std::uint64_t done, double) { progress.push_back(done); });
  sim.set_stop_check([] { return 0; });
  const RunResult r = sim.run(7);
  CHECK(r.steps == 7);
  CHECK_FALSE(r.stopped);
  CHECK(f.sys->step == 7);
  const std::vector<std::string> expected{"a@2", "b@3", "a@4", "s@5", "b@6", "a@6", "a@7"};
  CHECK(log == expected);
  // one progress report per chunk end: 2, 3, 4, 5, 6, 7
  CHECK(progress == std::vector<std::uint64_t>{2, 3, 4, 5, 6, 7});
  // periodic triggers follow the System's step counter across runs
  log.clear();
  sim.run(3);
  CHECK(log == std::vector<std::string>{"a@8", "b@9", "a@10"});
}

TEST_CASE("Simulation: chunks end at the next due step, at most max_chunk apart", "[run]") {
  Fixture f;
  Simulation sim = f.simulation();
  sim.set_stop_check([] { return 0; });
  sim.set_max_chunk(4);
  std::vector<std::uint64_t> ends;
  sim.set_progress([&](std::uint64_t done, double) { ends.push_back(done); });
  std::vector<std::string> log;
  sim.add(std::make_shared<Recorder>("r", log), Trigger::at({6}));
  sim.run(11);
  CHECK(ends == std::vector<std::uint64_t>{4, 6, 10, 11});
  CHECK_THROWS_AS(sim.set_max_chunk(0), InputError);
}

TEST_CASE("Simulation: a stop request ends the run at the step boundary with on_stop", "[run]") {
  Fixture f;
  Simulation sim = f.simulation();
  std::vector<std::string> log;
  sim.add(std::make_shared<Recorder>("every4", log), Trigger::every(4));
  sim.add(std::make_shared<Recorder>("ckpt", log), Trigger::every(4) | Trigger::on_stop());
  sim.add(std::make_shared<Recorder>("end", log), Trigger::at_end());
  int checks = 0;
  sim.set_stop_check([&] { return ++checks == 3 ? SIGTERM : 0; });  // after the 3rd chunk
  sim.set_max_chunk(5);
  const RunResult r = sim.run(100);
  // chunks end at 4, 8, 12: the stop comes at 12, where ckpt already ran (not twice)
  CHECK(r.stopped);
  CHECK(r.stop_signal == SIGTERM);
  CHECK(r.steps == 12);
  CHECK(f.sys->step == 12);
  CHECK(log == std::vector<std::string>{"every4@4", "ckpt@4", "every4@8", "ckpt@8", "every4@12",
                                        "ckpt@12"});
  // a stop between the periodic steps runs the on_stop operation there, and no at_end one
  log.clear();
  checks = 0;
  sim.set_stop_check([&] { return ++checks == 1 ? SIGINT : 0; });
  sim.set_max_chunk(2);
  const RunResult s = sim.run(100);
  CHECK(s.steps == 2);
  CHECK(log == std::vector<std::string>{"ckpt@14"});
}

TEST_CASE("Simulation: a real SIGTERM is honoured through core/stop_request", "[run]") {
  Fixture f;
  Simulation sim = f.simulation();
  install_stop_handlers();
  clear_stop_request();
  std::vector<std::string> log;
  sim.add(std::make_shared<FunctionOperation>("kill",
                                              [](Simulation&) {
                                                std::raise(SIGTERM);
                                                return true;
                                              }),
          Trigger::at({30}));
  sim.add(std::make_shared<Recorder>("ckpt", log), Trigger::on_stop());
  const RunResult r = sim.run(1000);
  clear_stop_request();
  install_stop_handlers();  // the handler restored the default action after the signal
  CHECK(r.stop_signal == SIGTERM);
  CHECK(r.steps == 30);
  CHECK(log == std::vector<std::string>{"ckpt@30"});
}

TEST_CASE("Simulation: an operation returning false ends the run without on_stop", "[run]") {
  Fixture f;
  Simulation sim = f.simulation();
  sim.set_stop_check([] { return 0; });
  std::vector<std::string> log;
  sim.add(std::make_shared<FunctionOperation>("enough",
                                              [](Simulation& s) { return s.system().step < 20; }),
          Trigger::every(10));
  sim.add(std::make_shared<Recorder>("ckpt", log), Trigger::on_stop());
  const RunResult r = sim.run(100);
  CHECK(r.steps == 20);
  CHECK(r.stopped);
  CHECK(r.stop_signal == 0);
  CHECK(log.empty());
}

TEST_CASE("Simulation: operations do not change the trajectory", "[run]") {
  Fixture plain, sampled;
  plain.dyn->run(*plain.sys, *plain.ff, 137);
  Simulation sim = sampled.simulation();
  sim.set_stop_check([] { return 0; });
  double energy = 0.0;
  sim.add(std::make_shared<FunctionOperation>(
              "energy",
              [&](Simulation& s) {
                energy = observe_energies(s.system(), s.forces()).total.energy;
                return true;
              }),
          Trigger::every(7));
  sim.run(137);
  CHECK(energy != 0.0);
  REQUIRE(plain.sys->n_sites() == sampled.sys->n_sites());
  for (std::size_t i = 0; i < plain.sys->n_sites(); ++i) {
    REQUIRE(plain.sys->sites().pos[i] == sampled.sys->sites().pos[i]);
    REQUIRE(plain.sys->sites().vel[i] == sampled.sys->sites().vel[i]);
  }
}

TEST_CASE("Kinetic temperature and Maxwell-Boltzmann velocities", "[run]") {
  System sys = test::random_spheres(4000, 0.2, false, 3);
  const auto all = test::all_sites(sys);
  set_maxwell_boltzmann(sys, all, 0.25);
  CHECK(temperature(sys, all) == Approx(0.25).epsilon(0.05));
  CHECK(std::isnan(temperature(sys, {})));  // undefined, not a frozen group
  const Vec3 v0 = sys.sites().vel[0];
  set_maxwell_boltzmann(sys, {0}, 0.25);  // keyed by seed, step and site: the same draw
  CHECK(sys.sites().vel[0] == v0);
  CHECK_THROWS_WITH(set_maxwell_boltzmann(sys, {4000}, 1.0),
                    Catch::Contains("site 4000 is outside [0, 4000)"));
}

TEST_CASE("Maxwell-Boltzmann velocities of sites heavier than 1: each component has variance kT/m",
          "[run]") {
  // The draw must scale with the site's own mass (vertices may be heavier than the cells):
  // <v_a^2> = kT / m, checked from the velocities directly and through m <v^2> / 3.
  // 4000 sites, 12000 components: relative error of the variance ~1.3 %, 5 % is ~4 sigma.
  System sys = test::random_spheres(4000, 0.2, false, 11);
  const auto all = test::all_sites(sys);
  const double mass = 4.0, kT = 0.25;
  set_masses(sys, all, mass);
  set_maxwell_boltzmann(sys, all, kT);
  double v2 = 0.0;
  for (int i : all) v2 += sys.sites().vel[i].squaredNorm();
  CHECK(v2 / (3.0 * double(all.size())) == Approx(kT / mass).epsilon(0.05));
  CHECK(temperature(sys, all) == Approx(kT).epsilon(0.05));
}

TEST_CASE("set_masses: the group's masses change, velocities and other sites are kept", "[run]") {
  System sys = test::random_spheres(200, 0.2, false, 5);
  const auto all = test::all_sites(sys);
  set_maxwell_boltzmann(sys, all, 0.5);
  const std::vector<int> half(all.begin(), all.begin() + 100), rest(all.begin() + 100, all.end());
  const double T_half = temperature(sys, half), T_rest = temperature(sys, rest);
  const std::vector<Vec3> vel = sys.sites().vel;
  set_masses(sys, half, 4.5);
  // The kinetic temperature m <v^2>/3 follows the mass at fixed velocities.
  CHECK(temperature(sys, half) == Approx(4.5 * T_half).epsilon(1e-12));
  CHECK(temperature(sys, rest) == T_rest);
  CHECK(sys.sites().vel == vel);
  for (int i : half) CHECK(sys.sites().mass[i] == 4.5);
  for (int i : rest) CHECK(sys.sites().mass[i] == 1.0);
  CHECK_THROWS_WITH(set_masses(sys, half, 0.0),
                    Catch::Contains("mass = 0.000000 must be finite and > 0"));
  CHECK_THROWS_WITH(set_masses(sys, half, std::nan("")), Catch::Contains("must be finite and > 0"));
  CHECK_THROWS_WITH(set_masses(sys, {200}, 2.0), Catch::Contains("site 200 is outside [0, 200)"));
  CHECK(sys.sites().mass[0] == 4.5);  // a refused call changes nothing
}

TEST_CASE("observe_energies names the terms and restores the site forces", "[run]") {
  Fixture f;
  f.ff->add(std::make_shared<ContactForce>(ContactParams{}));
  f.dyn->run(*f.sys, *f.ff, 5);
  const std::vector<Vec3> before = f.sys->sites().force;
  const EnergyTerms e = observe_energies(*f.sys, *f.ff);
  CHECK(e.names == std::vector<std::string>{"contact", "contact2"});
  CHECK(e.energies[0] == e.energies[1]);
  CHECK(e.total.energy == Approx(e.energies[0] + e.energies[1]));
  CHECK(f.sys->sites().force == before);
}
