#pragma once
// `invasim sweep ...`: parameter sweeps over a protocol (src/sweep/, docs/sweeps.md):
//   invasim sweep init SPEC.lua [--workspace DIR]
//   invasim sweep run WS [--jobs N] [--threads T]
//   invasim sweep status WS
//   invasim sweep collect WS [-o results.csv]
//   invasim sweep submit WS --slurm [--partition P] [--time T] [--cpus-per-task C]
//                         [--array-limit L] [--sbatch-arg ARG ...] [--dry-run]
//   invasim sweep analyze WS [-o DIR] [master_curve.py options]
//   invasim sweep job WS ID [--threads T]    (one point in this process: the Slurm tasks)
#include <string>
#include <vector>

namespace invasim::app {

// args: the arguments after `sweep`. Returns the exit status; throws UsageError on a bad
// command line and InputError on a bad spec or workspace.
int run_sweep_command(const std::vector<std::string>& args);

}  // namespace invasim::app
