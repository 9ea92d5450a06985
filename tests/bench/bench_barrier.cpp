// What a barrier costs inside a parallel region (docs/performance.md, "Team steps and the
// barrier"): libgomp's `omp barrier` under the process's wait policy (passive by default, as
// invasim runs) against invasim's TeamBarrier (core/team_barrier.hpp). Each region splits a fixed
// amount of work (divisions) over the team in k + 1 parts with a barrier between parts; prints
// microseconds per region for k = 0 and k = 8 with each barrier, and the work alone on one thread.
// Usage: bench_barrier [regions = 5000] [work = 200000]
//        (OMP_WAIT_POLICY=active or GOMP_SPINCOUNT=N in the environment to compare policies)
#include <omp.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "core/team_barrier.hpp"
#include "core/wait_policy.hpp"

using namespace invasim;

namespace {

double divisions(int n) {
  double s = 0.0;
  for (int i = 0; i < n; ++i) s += 1.0 / (i + 1.0);
  return s;
}

// Microseconds per region of `threads` threads, each region the work in barriers + 1 parts.
template <class Barrier>
double per_region(int regions, int work, int barriers, int threads, Barrier barrier) {
  std::vector<double> sink(64 * 8, 0.0);  // one cache line per thread
  const auto start = std::chrono::steady_clock::now();
  for (int r = 0; r < regions; ++r) {
#pragma omp parallel num_threads(threads)
    {
      const int me = omp_get_thread_num(), nt = omp_get_num_threads();
      for (int b = 0; b <= barriers; ++b) {
        sink[std::size_t(8 * me)] += divisions(work / nt / (barriers + 1));
        if (b < barriers) barrier();
      }
    }
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return 1e6 * seconds / regions;
}

}  // namespace

int main(int argc, char** argv) {
  use_passive_wait_policy_by_default(argv);  // as invasim does
  const int regions = argc > 1 ? std::atoi(argv[1]) : 5000;
  const int work = argc > 2 ? std::atoi(argv[2]) : 200000;
  const int threads = omp_get_max_threads();
  const char* policy = std::getenv("OMP_WAIT_POLICY");
  const char* spin = std::getenv("GOMP_SPINCOUNT");
  std::printf("%d threads, OMP_WAIT_POLICY=%s, GOMP_SPINCOUNT=%s; microseconds per region\n",
              threads, policy ? policy : "(unset)", spin ? spin : "(unset)");
  auto omp = [] {
#pragma omp barrier
  };
  std::printf("| barrier | empty region | work, no barrier | work + 8 barriers |\n");
  std::printf("|---|---|---|---|\n");
  std::printf("| omp barrier | %.1f | %.1f | %.1f |\n", per_region(regions, 0, 0, threads, omp),
              per_region(regions, work, 0, threads, omp),
              per_region(regions, work, 8, threads, omp));
  std::printf("| team_barrier | | | %.1f |\n", per_region(regions, work, 8, threads, team_barrier));
  std::printf("| (1 thread, no barrier) | | %.1f | |\n",
              per_region(regions, work, 0, 1, team_barrier));
  return 0;
}
