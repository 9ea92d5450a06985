#pragma once
// The numbers of the steady-state test of a run's averaging window (docs/validation.md,
// "Steady state"): the means m3, m4 of its two halves (the run's last two quarters) and the
// combined error of their difference. The quarters' errors come from one integrated
// autocorrelation time of the whole window, measured on its fluctuations about the drift
// (each quarter's own mean plus one common slope, so that a real step or ramp between the
// quarters inflates neither tau_int nor the variances). The test itself, |m4 - m3| against
// twice the error or a negligible drift, is the analysis's (scripts/invasim_analysis/steady.py),
// which computes the same numbers from series.csv; `sweep collect` writes these.
#include <cstddef>
#include <limits>
#include <span>

namespace invasim {

struct QuarterDrift {
  std::size_t quarter = 0;  // samples per quarter (the window's last 2 x quarter are used)
  double m3 = std::numeric_limits<double>::quiet_NaN(), m4 = m3;
  double drift = m3;      // m4 - m3
  double error = m3;      // sqrt(e3^2 + e4^2)
  double tau_int = m3;    // of the fluctuations about the drift, in samples
  bool resolved = false;  // Sokal's window criterion met (else the error is a lower bound)
};

// NaN numbers for fewer than 2 samples per quarter.
QuarterDrift quarter_drift(std::span<const double> window);

}  // namespace invasim
