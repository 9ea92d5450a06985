#pragma once
// `invasim sweep collect WS -o results.csv`: one row per state point, columns
//   job_id, status, wall_seconds [s], the state-point keys (sorted), then for every entry of
//   summary.json's "averages" that has a mean and an error (sorted by name) "<name> [unit]",
//   "<name>_error [unit]", "<name>_error_converged" (1 or 0), "<name>_drift [unit]" and
//   "<name>_drift_error [unit]" (unit from series.csv's header, no brackets when unitless; the
//   drift is the second half of the averaging window's mean minus the first half's, with the
//   steady-state test's error, window_statistics.hpp; the error and its convergence are
//   summary.json's, recomputed from series.csv for a summary without tau_int), then
//   tau_d [tau], tau_r [tau], tau_d_unresolved (1 when summary.json flags tau_d as shorter
//   than the correlator's interval, else 0).
// Floats as Python's repr (shortest round-trip text, always with a decimal point or an
// exponent), integers without one, so that 25 and 25.0 stay apart; strings as they are (quoted when
// they hold a comma or a quote); a job that is not done has its status and empty measurement cells,
// a done job without a readable summary.json is an IoError naming the file.
// docs/sweeps.md, "results.csv".
#include <ostream>

#include "sweep/workspace.hpp"

namespace invasim::sweep {

// Reads every point, then writes the table (nothing on an error); returns the number of rows.
int collect(const Workspace& ws, std::ostream& out);

}  // namespace invasim::sweep
