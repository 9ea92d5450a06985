#pragma once
// `invasim sweep status WS`: how many state points are pending, queued (Slurm), running,
// done, failed or interrupted, from the job documents, the job locks and, where Slurm's
// squeue is installed, the queue.
#include <map>
#include <ostream>
#include <string>

#include "sweep/workspace.hpp"

namespace invasim::sweep {

// Runs a shell command; returns pclose's status (-1 if it could not be started) and what it
// printed on standard output.
struct CommandOutput {
  int status = -1;
  std::string text;
};
CommandOutput run_command(const std::string& command);

// Slurm job id ("123" or "123_4") -> state (PENDING, RUNNING, ...) from `squeue -h -r`; empty
// when squeue is not installed or fails.
std::map<std::string, std::string> slurm_queue();

// A job's status, with Slurm's view: a submitted or running job the queue holds is "queued"
// (not started) or "running"; a submitted job the queue no longer holds is "pending"; else
// job_status (a "running" job whose lock nobody holds is "interrupted").
std::string effective_status(const fs::path& job_dir,
                             const std::map<std::string, std::string>& queue);

// The Slurm job that runs the point in `job_dir` by its document ("running" with a
// slurm_job_id the queue shows RUNNING) other than `own_slurm_id`, or "": the guard for file
// systems whose flock does not reach across nodes (a second node would take the lock too).
std::string running_slurm_job(const fs::path& job_dir, const std::string& own_slurm_id);

// Prints the counts (and the failed jobs' logs); returns 0.
int print_status(const Workspace& ws, std::ostream& out);

}  // namespace invasim::sweep
