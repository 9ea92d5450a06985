#pragma once
// When a loop is worth an OpenMP parallel region. Opening one costs a few microseconds on an
// idle machine and up to milliseconds when the cores are oversubscribed (threads spin-wait
// at barriers), more than a small loop's whole work: loops over fewer items than these
// thresholds run on the calling thread (`#pragma omp parallel for if (parallel_light(n))`).
// Results never depend on this choice (every parallel loop in invasim writes per item or
// reduces in a fixed order).
#include <omp.h>

#include <algorithm>
#include <cstddef>

namespace invasim {

// Loops with trivial work per item (a few flops: drift, kick, zeroing, FIRE updates) that open
// a parallel region of their own.
inline constexpr std::size_t kParallelLightItems = 16384;
// Loops with ~0.1-1 microsecond per item (pair forces of one site, neighbour-list rows).
inline constexpr std::size_t kParallelHeavyItems = 1024;
// A time step's team regions (ForceField::compute with the integrator's drift and kick inside,
// docs/performance.md "The parallel step"): one region carries the whole step's light work (drift,
// zeroing, wall and shape forces, Langevin kick with its random numbers: ~0.1 microsecond
// per site), so it pays from the same size as a heavy loop on an idle machine. Whether a time
// step gets more than one thread at all is measured by Dynamics (integrate/step_threads.hpp):
// next to a busy core a region this light can wait for a time slice.
inline constexpr std::size_t kParallelTeamItems = 1024;

inline bool parallel_light(std::size_t n) {
  return n >= kParallelLightItems;
}
inline bool parallel_heavy(std::size_t n) {
  return n >= kParallelHeavyItems;
}
inline bool parallel_team(std::size_t n) {
  return n >= kParallelTeamItems;
}

// The most threads a team can have that is started now, or the caller's own team inside a
// region: per-thread scratch is sized from it, and only ever grows (a team may still be using
// it). Inside a region omp_get_max_threads() is the next nesting level's count (1 under
// OMP_NUM_THREADS=4,1), not the current team's size.
inline std::size_t team_capacity() {
  return std::size_t(std::max({omp_get_max_threads(), omp_get_num_threads(), 1}));
}
// Grows a per-thread vector to team_capacity() entries (never shrinks it).
template <typename Vector>
void grow_to_team(Vector& per_thread) {
  if (const std::size_t n = team_capacity(); per_thread.size() < n) per_thread.resize(n);
}

// True on the thread of a team (or a serial caller) that writes the team's shared results.
inline bool team_leader() {
  return omp_get_thread_num() == 0;
}

}  // namespace invasim
