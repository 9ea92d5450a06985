// The time step's own barrier (core/team_barrier.hpp): no thread passes before all arrived,
// whether the others come within its spin or after it has gone to sleep; a team of one and
// code outside a parallel region pass at once; a waiting thread runs posted idle tasks
// (core/idle_tasks.hpp), each exactly once, and finish() runs the rest.
#include <omp.h>
#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include "core/idle_tasks.hpp"
#include "core/team_barrier.hpp"

using namespace invasim;

namespace {

// Runs `phases` barrier phases on `threads` threads; in each, every thread records its arrival,
// one thread (a different one each phase) arrives after `late`. After the barrier every
// thread checks that all threads arrived in this phase. Returns the number of failed checks.
int run_phases(int threads, int phases, std::chrono::microseconds late) {
  std::vector<std::atomic<int>> arrived(static_cast<std::size_t>(phases));
  std::atomic<int> failures{0};
#pragma omp parallel num_threads(threads)
  {
    const int me = omp_get_thread_num(), nt = omp_get_num_threads();
    for (int p = 0; p < phases; ++p) {
      if (p % nt == me && late.count() > 0) std::this_thread::sleep_for(late);
      arrived[std::size_t(p)].fetch_add(1);
      team_barrier();
      if (arrived[std::size_t(p)].load() != nt) failures.fetch_add(1);
    }
  }
  return failures.load();
}

}  // namespace

TEST_CASE("TeamBarrier: no thread passes before the whole team arrived") {
  SECTION("arrivals within the spin") {
    CHECK(run_phases(2, 20000, {}) == 0);
  }
  SECTION("a late thread: the others sleep and are woken") {
    // 2 ms is 40 times the spin: the waiting threads block on the futex.
    CHECK(TeamBarrier::kSpinSeconds < 2e-3);
    CHECK(run_phases(2, 40, std::chrono::microseconds(2000)) == 0);
  }
  SECTION("more threads than cores") {
    CHECK(run_phases(4, 2000, {}) == 0);
  }
}

TEST_CASE("TeamBarrier: a team of one and a serial caller pass at once") {
  team_barrier();  // outside any parallel region
  int passed = 0;
#pragma omp parallel num_threads(1)
  {
    team_barrier();
    ++passed;
  }
  CHECK(passed == 1);
  TeamBarrier own;
  own.wait(1);
}

TEST_CASE("IdleTasks: threads waiting at the team's barrier run posted tasks, each once") {
  const std::size_t n = 400;
  std::vector<std::atomic<int>> runs(n);
  std::vector<double> result(n, 0.0);
  std::atomic<int> in_region{0};
  idle_tasks().post(n, [&](std::size_t i) {
    runs[i].fetch_add(1);
    result[i] = 0.5 * double(i);
    if (omp_in_parallel()) in_region.fetch_add(1);
  });
  CHECK(idle_tasks().posted());
  // Thread 0 arrives late at every barrier, so thread 1 waits and takes tasks meanwhile.
#pragma omp parallel num_threads(2)
  for (int p = 0; p < 200; ++p) {
    if (omp_get_thread_num() == 0) std::this_thread::sleep_for(std::chrono::microseconds(20));
    team_barrier();
  }
  const int taken_in_waits = in_region.load();
  idle_tasks().finish();
  CHECK_FALSE(idle_tasks().posted());
  CHECK(taken_in_waits > 0);  // (with 2 threads: the barrier waits took tasks)
  for (std::size_t i = 0; i < n; ++i) {
    CHECK(runs[i].load() == 1);
    CHECK(result[i] == 0.5 * double(i));
  }
  // Posting again finishes what was posted before; finish() with nothing posted does nothing.
  int first = 0, second = 0;
  idle_tasks().post(3, [&](std::size_t) { ++first; });
  idle_tasks().post(2, [&](std::size_t) { ++second; });
  CHECK(first == 3);
  idle_tasks().finish();
  CHECK(second == 2);
  idle_tasks().finish();
}
