#pragma once
// The run loop (docs/architecture.md, "Run layer"), modelled on HOOMD-blue's System with its
// updaters/analyzers and triggers: a Simulation holds the System, its ForceField and the
// Dynamics that steps them, and an ordered list of operations, each with a Trigger.
//
// run(n) advances the System by n steps. It steps the Dynamics in chunks that end at the next
// step where some operation is due (at most set_max_chunk()'s length, 100 steps by default,
// never past the end), and at each chunk's end, in this fixed order:
//   1. every operation whose trigger is due at this step (every N / at steps; at the last step
//      of the run also the at_end ones), in the order they were added, each at most once;
//   2. the progress callback (steps done, simulated time);
//   3. the stop check: if a stop was requested (SIGINT / SIGTERM via core/stop_request, or an
//      operation's request_stop()), the on_stop operations not already run at this step run,
//      in order, and run() returns at this step boundary.
// The chunking does not change the trajectory (a Dynamics run in pieces equals one run).
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "forces/force.hpp"
#include "integrate/dynamics.hpp"
#include "run/operation.hpp"
#include "run/trigger.hpp"
#include "state/system.hpp"

namespace invasim {

// How a run(n) ended.
struct RunResult {
  std::uint64_t steps = 0;  // steps done
  int stop_signal = 0;      // the signal that stopped the run early (0: none)
  bool stopped = false;     // stopped early (by a signal or an operation's request_stop())
};

class Simulation {
 public:
  // Shared ownership: the Lua layer passes pointers that keep its own objects alive.
  Simulation(std::shared_ptr<System> system, std::shared_ptr<ForceField> forces,
             std::shared_ptr<Dynamics> dynamics);

  System& system() { return *system_; }
  ForceField& forces() { return *forces_; }
  Dynamics& dynamics() { return *dynamics_; }

  // One scheduled operation.
  struct Scheduled {
    std::shared_ptr<Operation> operation;
    Trigger trigger;
  };
  // Appends an operation; operations due at the same step run in the order added. Refused
  // during run() (from an operation): its schedule would start in the middle of the run.
  void add(std::shared_ptr<Operation> operation, Trigger trigger);
  const std::vector<Scheduled>& operations() const { return operations_; }

  using ProgressFn = std::function<void(std::uint64_t done, double time)>;
  void set_progress(ProgressFn progress) { progress_ = std::move(progress); }
  // Polled at every chunk end; returns the signal asking for a stop or 0 (default:
  // core/stop_request's stop_requested).
  using StopCheckFn = std::function<int()>;
  void set_stop_check(StopCheckFn check) { stop_check_ = std::move(check); }
  // Longest chunk between two stop checks / progress updates (default 100 steps).
  void set_max_chunk(std::uint64_t steps);

  // Advances the System by n steps (see the header comment for the order of events).
  RunResult run(std::uint64_t n);
  // Called by an operation: ends the current run at this step boundary (no on_stop ones).
  void request_stop() { stop_requested_ = true; }
  // Called by an operation that changed the state or the site forces.
  void state_changed() { dynamics_->invalidate(); }

 private:
  std::shared_ptr<System> system_;
  std::shared_ptr<ForceField> forces_;
  std::shared_ptr<Dynamics> dynamics_;
  std::vector<Scheduled> operations_;
  ProgressFn progress_;
  StopCheckFn stop_check_;
  std::uint64_t max_chunk_ = 100;
  bool stop_requested_ = false;
  bool running_ = false;  // inside run()
};

}  // namespace invasim
