#pragma once
// The bookkeeping around one run of a job, shared by `sweep run` (child processes) and
// `sweep job` (one job in this process, under Slurm): the job document before (running, who,
// where) and after (done / failed / interrupted, exit code, accumulated wall time).
#include <chrono>
#include <string>

#include "sweep/workspace.hpp"

namespace invasim::sweep {

class JobRecord {
 public:
  // Marks the job running: pid, host, start time, attempt count, version, git revision,
  // Slurm job id (from SLURM_ARRAY_JOB_ID/SLURM_ARRAY_TASK_ID or SLURM_JOB_ID) if any.
  JobRecord(const fs::path& job_dir, int pid);
  // Records the end: exit code, and status done (0), interrupted (stopped by a signal) or
  // failed; returns the status.
  std::string finish(int exit_code, bool stopped);
  const fs::path& dir() const { return dir_; }
  fs::path log_path() const { return dir_ / "run.log"; }

 private:
  fs::path dir_;
  std::chrono::steady_clock::time_point start_;
};

// Now as an ISO 8601 UTC time stamp.
std::string utc_now();

}  // namespace invasim::sweep
