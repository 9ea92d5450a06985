#pragma once
// `invasim sweep run WS`: runs the workspace's unfinished jobs on this machine, `jobs` at a
// time, each as a child process `invasim sweep job WS ID --threads T`, which takes the job's
// lock, runs it (`invasim run PROTOCOL --out JOBDIR --set ... [--from PREP]`, or `--resume
// JOBDIR` when it has started before) and records its end in the job document itself: a point
// ends in the state its run ended in even when this runner was killed meanwhile. The shared
// preparation runs first, alone, with the same --threads (a local run and a Slurm run with
// --cpus-per-task `threads` give the same numbers), unless every point is done. Finished jobs
// are skipped, so are jobs another runner holds (their lock). SIGINT / SIGTERM (and SIGHUP,
// passed on as SIGTERM) are forwarded once to every child, which checkpoints and stops; no
// new job starts; the jobs are recorded as interrupted. A failed job does not stop the
// others. At the end every unfinished point is listed with why (failed and its log,
// interrupted, running elsewhere and where, not started).
#include <ostream>
#include <string>

#include "sweep/workspace.hpp"

namespace invasim::sweep {

struct LocalRunSettings {
  int jobs = 1;            // children at a time
  int threads = 1;         // --threads of each child
  std::string executable;  // this invasim binary
};

// Returns the exit status: 0 if every point is done at the end, 1 otherwise.
int run_local(const Workspace& ws, const LocalRunSettings& settings, std::ostream& out);

}  // namespace invasim::sweep
