#pragma once
// The barrier inside a time step's parallel region (docs/performance.md, "Team steps and the
// barrier"). libgomp's own barriers follow the wait policy: passive (invasim's default, for shared
// cores) puts a waiting thread to sleep at once, and waking it costs ~20-40 us on a virtual
// machine, about a tenth of a whole step of the paper's system at 2 threads; a spinning policy
// (GOMP_SPINCOUNT) would also make the pool's idle thread spin between steps that the measured
// choice runs on one thread, which costs other processes' cores. This barrier spins for a
// bounded time (about one wake-up's cost: the most a wait can waste is then twice the least it
// could cost), then sleeps on a futex (std::atomic::wait), so it pays only where a team step
// runs and never holds a core for long; a thread whose waits keep outlasting the spin (its
// partner shares a core) spins less and less.
#include <atomic>

namespace invasim {

class TeamBarrier {
 public:
  // How long a waiting thread spins before it sleeps: at most kSpinSeconds, less on a thread
  // whose recent waits outlasted the spin (adaptive, see wait()), never below kMinSpinSeconds.
  static constexpr double kSpinSeconds = 50e-6, kMinSpinSeconds = 1e-6;
  // Waits until `team_size` threads have called wait() for this phase. Every thread of the team
  // must call it the same number of times; team_size 1 returns at once.
  void wait(int team_size);

 private:
  std::atomic<int> arrived_{0};
  std::atomic<unsigned> phase_{0};
};

// The barrier of the calling OpenMP team (a no-op outside a parallel region or in a team of
// one). Called by every thread of the team, where an `omp barrier` would stand; every barrier of
// the time step's region uses it (a worksharing loop there takes `nowait` and calls it after).
// One process-wide object: invasim runs one team at a time (nested regions are inactive).
void team_barrier();

}  // namespace invasim
