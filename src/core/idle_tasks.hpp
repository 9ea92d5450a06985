#pragma once
// Work that the threads of a time step's team take up while they wait at a TeamBarrier
// (docs/performance.md, "Measurements"): the phases of a team step end at barriers, and the
// thread that arrives first waits for the other, ~10 % of a paper production's samples at 2
// threads. An owner posts a set of independent tasks (the correlators' (origin, sample, block)
// terms) between two runs; a waiting thread runs one task at a time while its barrier has not
// released; the owner finishes what is left (on all threads) before it reads the results. Each
// task writes only its own result, so who ran it does not change any bit.
#include <atomic>
#include <cstddef>
#include <functional>

namespace invasim {

class IdleTasks {
 public:
  // Makes tasks 0 .. n-1 of `run` available; finishes the tasks posted before first. Called
  // outside any parallel region (the region's start publishes the tasks to its threads).
  void post(std::size_t n, std::function<void(std::size_t)> run);
  // Runs one task not yet taken on the calling thread; false when none is left.
  bool run_one();
  // Runs the tasks no thread has taken (on every thread of a parallel region of its own when
  // there are many), waits for those in progress, and empties the queue; afterwards every
  // task's results are visible to the caller. Called outside any parallel region.
  void finish();
  // Whether tasks are posted and not yet finished.
  bool posted() const { return total_.load(std::memory_order_acquire) > 0; }

 private:
  std::function<void(std::size_t)> run_;
  std::atomic<std::size_t> total_{0}, next_{0}, done_{0};
};

// The process-wide queue that TeamBarrier::wait takes tasks from (invasim runs one team at a
// time, and its owners post and finish between the team's regions).
IdleTasks& idle_tasks();

}  // namespace invasim
