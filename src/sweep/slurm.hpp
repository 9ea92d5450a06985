#pragma once
// `invasim sweep submit WS --slurm`: the points that are not done (nor queued or running)
// become Slurm job arrays of at most MaxArraySize tasks each (a cluster refuses larger
// ones). In WS/slurm/submit-K/ it writes, per array j = 1, 2, ..., points-j.txt (one job id
// per line: array task i runs line i + 1) and array-j.sbatch (each task runs
// `invasim sweep job WS ID --threads $SLURM_CPUS_PER_TASK`) and, when the shared preparation
// is not done, prep.sbatch, submitted first; the array then waits for it with
// --dependency=afterok (with --kill-on-invalid-dep=yes: Slurm drops the array if the
// preparation fails, rather than holding it pending forever). Both are submitted with `sbatch
// --parsable`; the Slurm job ids go to the job documents (status "submitted") and
// WS/slurm/submissions.json. A task killed by its time limit was stopped by SIGTERM and
// checkpointed; submitting again continues it.
#include <ostream>
#include <string>
#include <vector>

#include "sweep/workspace.hpp"

namespace invasim::sweep {

struct SlurmOptions {
  std::string partition;          // --partition (default: the cluster's default)
  std::string time;               // --time (default: the partition's limit)
  int cpus_per_task = 1;          // --cpus-per-task, also the runs' --threads
  int array_limit = 0;            // --array-limit: tasks at a time (0: no limit)
  int max_array_size = 0;         // --max-array-size: tasks per array (0: the cluster's
                                  // MaxArraySize from `scontrol show config`, else 1001)
  std::string mem, account, qos;  // --mem, --account, --qos (checked before submitting)
  // The preparation's own --time, --mem and --cpus-per-task (--prep-time ...; default: the
  // points' values): a compression needs other resources than a production run.
  std::string prep_time, prep_mem;
  int prep_cpus_per_task = 0;
  int signal_before = 300;         // --signal-before S: SIGTERM S seconds before the time limit
  int max_requeues = 3;            // --max-requeues N: a point stopped by it requeues itself
  std::vector<std::string> extra;  // --sbatch-arg ARG: more #SBATCH lines
  bool dry_run = false;            // write the scripts, submit nothing
  std::string executable;          // this invasim binary
};

// Returns 0, or 1 if sbatch failed (its message printed).
int submit_slurm(const Workspace& ws, const SlurmOptions& options, std::ostream& out);

// Checks the values of the resource options (time as Slurm reads it: M, M:S, H:M:S, D-H,
// D-H:M, D-H:M:S; memory as digits with an optional K/M/G/T; account and QOS names of
// letters, digits, '_', '-', '.'); a bad one is an input error naming the option and value.
void check_slurm_options(const SlurmOptions& options);

// Called by a point's `sweep job` under Slurm when its run was stopped (the time limit's
// warning signal): requeues this Slurm job (`scontrol requeue`) unless the point has used
// `max_requeues` requeues, marking the point "submitted" again; returns whether it did.
bool requeue_stopped_point(const Workspace& ws, const std::string& id, int max_requeues,
                           std::ostream& out);

// Called by the shared preparation's `sweep job` when it did not finish under Slurm job
// `prep_job`: cancels (scancel) the arrays submitted after it and returns their points to
// "pending" with a "cancelled" note naming the preparation's failure and log, so that `status`
// says why and `submit` submits them again (with a new preparation). Returns the number of
// points returned to pending.
int cancel_after_failed_prep(const Workspace& ws, const std::string& prep_job, std::ostream& out);

}  // namespace invasim::sweep
