#pragma once
// The drift of a run's averaged quantities over their averaging window, from series.csv:
// the mean of the window's second half minus the mean of its first half (the window is the
// last `samples` rows, as summary.json's "averages" states). A state point whose box length
// or interface area still drifts is not a steady state; `sweep collect` writes these as
// "<name>_drift" columns so that the analysis can tell (docs/sweeps.md, "results.csv").
#include <filesystem>
#include <map>
#include <string>

#include "io/json.hpp"

namespace invasim::sweep {

namespace fs = std::filesystem;

// A series.csv column name without its unit: "T_c [eps_c]" -> "T_c".
std::string bare_column_name(const std::string& column);

// For every entry of `averages` ({"name": {"samples": n, ...}}) with n >= 2 and a column of
// that name in `series` (units in brackets ignored) whose last n values are finite numbers:
// mean of the last floor(n/2) values minus the mean of the floor(n/2) before them (the middle
// value of an odd window is left out). Quantities without such data are absent.
std::map<std::string, double> window_drifts(const fs::path& series, const Json& averages);

}  // namespace invasim::sweep
