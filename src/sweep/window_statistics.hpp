#pragma once
// A run's averaged quantities over their averaging window, recomputed from series.csv for
// the results table: the drift between the window's two halves with its error (the numbers of
// the steady-state test, measure/quarter_drift.hpp) and the error of the window's mean (the
// summary's estimator, measure/mean_error.hpp; a summary.json written before it held errors by
// blocking). A state point whose interface area or box length still drifts is not a steady
// state; `sweep collect` writes these columns so that the analysis can tell from the table
// alone (docs/sweeps.md, "results.csv").
#include <filesystem>
#include <map>
#include <string>

#include "io/json.hpp"

namespace invasim::sweep {

namespace fs = std::filesystem;

// A series.csv column name without its unit: "T_c [eps_c]" -> "T_c".
std::string bare_column_name(const std::string& column);

struct WindowStatistics {
  double drift = 0.0;            // mean of the window's second half minus its first half's
  double drift_error = 0.0;      // their combined error (NaN for fewer than 2 rows per half)
  double error = 0.0;            // standard error of the window's mean
  bool error_converged = false;  // Sokal's window criterion met for `error`
};

// For every entry of `averages` ({"name": {"samples": n, ...}}) with n >= 2 and a column of
// that name in `series` (units in brackets ignored) whose last n values are finite numbers:
// the statistics of those n values (the halves are the last 2 floor(n/2) of them: the first
// value of an odd window is left out). Quantities without such data are absent.
std::map<std::string, WindowStatistics> window_statistics(const fs::path& series,
                                                          const Json& averages);

}  // namespace invasim::sweep
