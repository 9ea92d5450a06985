#include "core/team_barrier.hpp"

#include "core/idle_tasks.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>

namespace invasim {

namespace {
inline void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#elif defined(__aarch64__)
  asm volatile("yield");
#endif
}
}  // namespace

void TeamBarrier::wait(int team_size) {
  if (team_size <= 1) return;
  // The phase is read before arriving: the last thread to arrive advances it only after every
  // other thread has read it.
  const unsigned phase = phase_.load(std::memory_order_acquire);
  if (arrived_.fetch_add(1, std::memory_order_acq_rel) == team_size - 1) {
    arrived_.store(0, std::memory_order_relaxed);  // (published by the release below)
    phase_.fetch_add(1, std::memory_order_release);
    phase_.notify_all();  // (no system call when nobody sleeps)
    return;
  }
  // This thread's spin budget, from how long its waits take: a wait short enough that the
  // full spin would have covered it (allowing for the wake-up's latency when it slept) doubles
  // the budget, up to kSpinSeconds; a longer one halves it, down to kMinSpinSeconds. Where the
  // team's threads have their cores the waits are short and the budget stays full; where they
  // share a core with each other or with other work, waits last time slices (a spinning thread
  // would take the time of the one it waits for) and the budget falls: passive waiting.
  thread_local double budget = kSpinSeconds;
  using Clock = std::chrono::steady_clock;
  // While the barrier holds, the thread first runs posted idle tasks (core/idle_tasks.hpp), one
  // at a time; the spin and its budget count from when none is left.
  IdleTasks& tasks = idle_tasks();
  bool released = false;
  while (tasks.posted() && !released) {
    if (!tasks.run_one()) break;
    released = phase_.load(std::memory_order_acquire) != phase;
  }
  if (released) return;
  const auto start = Clock::now();
  const auto deadline =
      start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(budget));
  for (int k = 1;; ++k) {
    if (phase_.load(std::memory_order_acquire) != phase) {
      released = true;
      break;
    }
    cpu_relax();
    if (k % 32 == 0 && Clock::now() > deadline) break;
  }
  if (!released)
    while (phase_.load(std::memory_order_acquire) == phase)
      phase_.wait(phase, std::memory_order_acquire);
  const double waited = std::chrono::duration<double>(Clock::now() - start).count();
  budget = waited <= 2.0 * kSpinSeconds ? std::min(2.0 * budget, kSpinSeconds)
                                        : std::max(0.5 * budget, kMinSpinSeconds);
}

void team_barrier() {
  static TeamBarrier barrier;
  barrier.wait(omp_get_num_threads());
}

}  // namespace invasim
