#pragma once
// Mean and standard error of a correlated time series by blocking (Flyvbjerg & Petersen,
// J. Chem. Phys. 91, 461 (1989)): the series is repeatedly halved by averaging neighbouring
// pairs; at block size B = 2^k the naive standard error of the n_B block means grows with B
// until the blocks are uncorrelated, then stays on a plateau. The plateau level is chosen by
// the criterion of Lee et al. (Phys. Rev. E 83, 066706 (2011)): the smallest B with
// B^3 > 2 n (sigma_B^2 / sigma_1^2)^2, where sigma_B^2 / sigma_1^2 = (error_B / error_1)^2
// estimates 2 tau_int. It balances the bias of too-small blocks (~ tau / B) against the
// noise of too few blocks (~ sqrt(2 B / n)). Used for the end-of-run summary of thermo
// columns (time averages over the last part of a run, with error bars).
#include <cstddef>
#include <limits>
#include <span>
#include <vector>

namespace invasim {

// One blocking level: blocks of block_size samples (the first n_blocks * block_size
// samples of the series), the standard error of the mean they give and its own uncertainty.
struct BlockingLevel {
  std::size_t block_size = 0, n_blocks = 0;
  double error = 0.0;           // sqrt(s^2 / (n_blocks - 1)), s^2 the variance of block means
  double error_of_error = 0.0;  // error / sqrt(2 (n_blocks - 1))
};

struct BlockingOptions {
  // Levels with fewer blocks are not considered (their error estimate is too noisy).
  std::size_t min_blocks = 16;
  void validate() const;
};

struct BlockAverage {
  std::size_t n = 0;                                        // samples used
  double mean = std::numeric_limits<double>::quiet_NaN();   // mean of all n samples
  double error = std::numeric_limits<double>::quiet_NaN();  // standard error (plateau level)
  double error_of_error = std::numeric_limits<double>::quiet_NaN();
  double naive_error = std::numeric_limits<double>::quiet_NaN();  // as if uncorrelated
  std::size_t block_size = 0, n_blocks = 0;                       // the level chosen
  // True when the criterion was met with >= min_blocks blocks. False: the series is too short
  // for its correlation time and `error` (from the last usable level) is a lower bound.
  bool plateau = false;
  std::vector<BlockingLevel> levels;  // every level with >= 2 blocks
};

// Blocking analysis of the whole series. n = 0 gives NaN mean; n < 2 a NaN error.
BlockAverage block_average(std::span<const double> x, const BlockingOptions& options = {});
// The same over the last floor(fraction * n) samples, 0 < fraction <= 1 (the production
// part of a run, after the transient).
BlockAverage block_average_tail(std::span<const double> x, double fraction,
                                const BlockingOptions& options = {});

}  // namespace invasim
