#pragma once
// A test hook for the thread-independence tests (docs/reliability.md), off unless its
// environment variable is set: INVASIM_TEST_TEAM_STEPS=1 starts every StepThreads (a
// Dynamics', a FIRE's, a compression's) in Mode::kAll, so that whenever OpenMP has more than
// one thread a step of a large enough System (core/parallel.hpp, kParallelTeamItems) runs in
// the parallel team, instead of the measured choice of integrate/step_threads.hpp (which next
// to a busy core may keep one thread). The tests check that it did with
// Dynamics::parallel_steps() (Lua dyn:parallel_steps()).

namespace invasim {

// True when INVASIM_TEST_TEAM_STEPS=1.
bool team_steps_forced();

}  // namespace invasim
