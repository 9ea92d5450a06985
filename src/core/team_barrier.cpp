#include "core/team_barrier.hpp"

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
  // This thread's spin budget: halved by every wait that outlasts it, doubled (up to
  // kSpinSeconds) by every wait that ends within it. Where the team's threads get their cores
  // the waits are short and the budget stays full; where they share a core with each other or
  // with other work (a thread that spins then takes the time of the one it waits for), most
  // waits outlast it and it falls to kMinSpinSeconds within a few barriers: passive waiting.
  thread_local double budget = kSpinSeconds;
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const auto deadline =
      start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(budget));
  for (int k = 1;; ++k) {
    if (phase_.load(std::memory_order_acquire) != phase) {
      budget = std::min(2.0 * budget, kSpinSeconds);
      return;
    }
    cpu_relax();
    if (k % 32 == 0 && Clock::now() > deadline) break;
  }
  budget = std::max(0.5 * budget, kMinSpinSeconds);
  while (phase_.load(std::memory_order_acquire) == phase)
    phase_.wait(phase, std::memory_order_acquire);
}

void team_barrier() {
  static TeamBarrier barrier;
  barrier.wait(omp_get_num_threads());
}

}  // namespace invasim
