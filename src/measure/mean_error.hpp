#pragma once
// Mean and standard error of a correlated time series from its integrated autocorrelation
// time tau_int (in samples): error^2 = 2 tau_int Var / n. tau_int(W) = 1/2 + sum_(t=1..W)
// rho(t) is summed up to Sokal's automatic window, the smallest W with W >= kSokalC tau_int(W)
// (Madras and Sokal, J. Stat. Phys. 50, 109 (1988)), at most n/3: beyond it the bias of the
// subtracted mean (every lag's autocovariance low by C_F/n, C_F = 2 tau_int Var; Wolff,
// Comput. Phys. Commun. 156, 143 (2004)), corrected by the factor 1/(1 - (2W + 1)/n), would
// exceed 3. Where the criterion is not met by the cap, tau_int and the error are lower bounds
// and the result says so. Used for the end-of-run summary of thermo columns (time averages
// over the last part of a run, with error bars; docs/measurements_dynamics.md, "Summary").
// The validation's steady-state test (scripts/invasim_analysis/steady.py, integrated_time)
// is the same estimator, with the window's drift fitted instead of its mean alone.
#include <cstddef>
#include <limits>
#include <span>

namespace invasim {

// Sokal's window constant (4-6 suits autocorrelations that decay about exponentially).
inline constexpr double kSokalC = 5.0;
// The window's cap: fitted (2W + 1)/n at most this share of the samples.
inline constexpr double kMaxWindowShare = 2.0 / 3.0;

// The integrated autocorrelation time of fluctuations r about `fitted` least-squares
// parameters (the mean alone: 1), by Sokal's window capped at fitted (2W + 1)/n <=
// kMaxWindowShare, the fit's bias (every lag low by fitted C_F/n) corrected.
struct IntegratedTime {
  double tau_int = std::numeric_limits<double>::quiet_NaN();  // samples, at least 1/2
  double removed = std::numeric_limits<double>::quiet_NaN();  // variance the fit took out
  std::size_t window = 0;                                     // Sokal's W
  bool resolved = false;  // the criterion met within the cap (else tau_int a lower bound)
};
// NaN for n <= max(1, fitted); tau_int = 1/2, resolved, for fluctuations that are all zero.
IntegratedTime integrated_time(std::span<const double> r, std::size_t fitted);
// The standard error of a mean from its fluctuations r (all or part of those `t` was
// measured on): sqrt((mean(r^2) + t.removed) 2 t.tau_int / n).
double error_of_mean(std::span<const double> r, const IntegratedTime& t);

struct MeanError {
  std::size_t n = 0;                                          // samples used
  double mean = std::numeric_limits<double>::quiet_NaN();     // mean of all n samples
  double error = std::numeric_limits<double>::quiet_NaN();    // standard error of the mean
  double tau_int = std::numeric_limits<double>::quiet_NaN();  // samples; 1/2: independent
  std::size_t window = 0;                                     // Sokal's W
  // True when Sokal's criterion was met within the cap. False: the series is too short for
  // its correlation time (or has fewer than 5 samples), and tau_int and `error` are lower
  // bounds.
  bool resolved = false;
};

// The estimate over the whole series. n = 0 gives a NaN mean; n < 2 a NaN error. A constant
// series has error 0, resolved.
MeanError mean_error(std::span<const double> x);
// The same over the last floor(fraction * n) samples, 0 < fraction <= 1 (the production
// part of a run, after the transient).
MeanError mean_error_tail(std::span<const double> x, double fraction);

}  // namespace invasim
