#pragma once
// A test hook for the thread-independence tests (docs/reliability.md), off unless its
// environment variable is set: INVASIM_TEST_TEAM_STEPS=1 makes every Dynamics run each step of
// a large enough System (core/parallel.hpp, kParallelTeamItems) in its parallel team whenever
// OpenMP has more than one thread, instead of the measured choice of integrate/step_threads.hpp
// (which next to a busy core may keep one thread), and prints at exit
// "test hook: N steps ran in parallel teams" to stderr, so that a run at 2 threads is known
// to have taken the parallel path it is compared on.
#include <cstdint>

namespace invasim {

// True when INVASIM_TEST_TEAM_STEPS=1.
bool team_steps_forced();
// Adds n steps run in a parallel team to the count printed at exit (only when forced).
void count_team_steps(std::uint64_t n);

}  // namespace invasim
