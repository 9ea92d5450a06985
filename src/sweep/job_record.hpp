#pragma once
// The bookkeeping around one run of a job, shared by `sweep run` (child processes) and
// `sweep job` (one job in this process, under Slurm): the job document before (running, who,
// where) and after (done / failed / interrupted, exit code, accumulated wall time).
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

#include "io/run_lock.hpp"
#include "sweep/workspace.hpp"

namespace invasim::sweep {

//
// wall_seconds counts every attempt, also one killed without recording its end (SIGKILL, a
// machine lost): while the run goes on, a heartbeat writes the attempt's time so far to the
// document (attempt_seconds, every `heartbeat`), and the next attempt (or the runner that
// finds the child dead) adds what the killed one left there.
class JobRecord {
 public:
  // Marks the job running: pid, host, start time, attempt count, version, git revision,
  // Slurm job id (from SLURM_ARRAY_JOB_ID/SLURM_ARRAY_TASK_ID or SLURM_JOB_ID) if any; adds a
  // killed attempt's attempt_seconds to wall_seconds; starts the heartbeat.
  JobRecord(const fs::path& job_dir, int pid,
            std::chrono::duration<double> heartbeat = std::chrono::seconds(60));
  ~JobRecord();  // stops the heartbeat
  JobRecord(const JobRecord&) = delete;
  JobRecord& operator=(const JobRecord&) = delete;
  // Records the end: exit code, and status done (0), interrupted (stopped by a signal) or
  // failed, the attempt's time added to wall_seconds; returns the status.
  std::string finish(int exit_code, bool stopped);
  fs::path log_path() const { return dir_ / "run.log"; }

 private:
  void stop_heartbeat();
  double elapsed() const;
  fs::path dir_;
  std::chrono::steady_clock::time_point start_;
  std::mutex mutex_;  // guards the document between the heartbeat and finish
  std::condition_variable wake_;
  bool stopping_ = false;
  std::thread heartbeat_;
};

// Records the end of a run of the job in its document (status done for exit code 0, else
// interrupted when stopped by a signal, else failed; the exit code; `seconds`, the whole
// attempt, added to wall_seconds, replacing its heartbeat's attempt_seconds) and returns the
// status. JobRecord::finish, and `sweep run` for a child that died before it could record
// its own end.
std::string record_end(const fs::path& job_dir, int exit_code, bool stopped, double seconds);

// `sweep job`'s exit status when another runner holds the point (EX_TEMPFAIL): not a failure
// of the point, which `sweep run` reports as running elsewhere.
inline constexpr int kJobBusyExitCode = 75;

// This process's Slurm job: "ARRAYJOB_TASK" (SLURM_ARRAY_JOB_ID, SLURM_ARRAY_TASK_ID), else
// SLURM_JOB_ID, else "" (not under Slurm).
std::string current_slurm_job_id();

}  // namespace invasim::sweep
