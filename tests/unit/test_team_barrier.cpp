// The time step's own barrier (core/team_barrier.hpp): no thread passes before all arrived,
// whether the others come within its spin or after it has gone to sleep; a team of one and
// code outside a parallel region pass at once.
#include <omp.h>
#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

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
