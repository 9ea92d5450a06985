#pragma once
// How many OpenMP threads a time step uses (docs/performance.md, "The parallel step").
// A step's parallel regions pay only if their work outweighs waking the other threads and
// waiting for them at the barriers: on an idle machine that holds for ~1 ms steps, but next to
// a busy core a woken thread may wait for a time slice, and a light step (6000 free particles,
// 0.6 ms) became several times slower with 2 threads than with 1. So Dynamics measures: it
// times windows of steps with 1 thread and with all threads and runs the faster, checking
// again from time to time. The results never depend on the choice (every step is bit-identical
// for any thread count); only the speed does.
#include <chrono>
#include <cstdint>

#include "integrate/test_hooks.hpp"

namespace invasim {

class StepThreads {
 public:
  enum class Mode {
    kAuto,  // measured choice between 1 thread and all (the default)
    kAll,   // every step with all threads (tests of the parallel path, benchmarks)
  };
  // A window lasts at least this long and this many steps (so that list builds average out).
  static constexpr double kWindowSeconds = 0.05;
  static constexpr std::uint64_t kMinWindowSteps = 8;
  // Steps cheaper than this at 1 thread never try the team (a wake-up costs ~10 us).
  static constexpr double kMinTeamStepSeconds = 50e-6;
  // The team is chosen if its window takes less than this fraction of the 1-thread window's
  // time (1 thread leaves the other cores to other work).
  static constexpr double kTeamGain = 0.95;
  // A held team window slower than this factor times the last 1-thread window measures again
  // at once (the machine got busier; the margin keeps ordinary noise from triggering it).
  static constexpr double kRecheckFactor = 1.25;
  // Windows between two measurements: from kMinHold, doubling while the choice stays the same.
  static constexpr std::uint64_t kMinHold = 8, kMaxHold = 512;

  void set_mode(Mode mode);
  // Threads for the next step: 1 or omp_get_max_threads().
  int begin_step();
  // The step begun last took `seconds` of wall time.
  void end_step(double seconds);
  // Steps run with all threads (> 1) and with one thread by choice, since construction.
  std::uint64_t team_steps() const { return team_steps_; }
  std::uint64_t serial_steps() const { return serial_steps_; }

 private:
  enum class Phase { kSerialWindow, kTeamWindow, kHold };
  void start_measuring();
  void choose(bool team);
  Mode mode_ = team_steps_forced() ? Mode::kAll : Mode::kAuto;
  int max_threads_ = 0;
  bool team_now_ = false;  // the thread count of the step begun last
  Phase phase_ = Phase::kSerialWindow;
  double serial_time_ = 0.0, team_time_ = 0.0, hold_time_ = 0.0;
  std::uint64_t serial_n_ = 0, team_n_ = 0, window_ = 0, hold_n_ = 0, hold_left_ = 0;
  bool team_chosen_ = false, decided_ = false;
  std::uint64_t hold_windows_ = kMinHold;
  std::uint64_t team_steps_ = 0, serial_steps_ = 0;
};

// Sets the calling thread's OpenMP thread count for the lifetime of the object (restores it).
class ThreadCountScope {
 public:
  explicit ThreadCountScope(int threads);
  ~ThreadCountScope();
  ThreadCountScope(const ThreadCountScope&) = delete;
  ThreadCountScope& operator=(const ThreadCountScope&) = delete;

 private:
  int saved_;
};

// One measured step for the lifetime of the object: the thread count StepThreads chose, and
// the step's wall time handed back to it on destruction (whichever way the step's scope ends).
// FIRE's iterations use it (a minimisation's loop has several exits).
class MeasuredStep {
 public:
  explicit MeasuredStep(StepThreads& threads);
  ~MeasuredStep();
  MeasuredStep(const MeasuredStep&) = delete;
  MeasuredStep& operator=(const MeasuredStep&) = delete;

 private:
  StepThreads& threads_;
  ThreadCountScope scope_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace invasim
