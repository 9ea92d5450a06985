#include "measure/block_average.hpp"

#include <cmath>

#include "core/errors.hpp"

namespace invasim {

void BlockingOptions::validate() const {
  if (min_blocks < 2) fail_input("blocking: min_blocks = ", min_blocks, " must be >= 2");
}

namespace {
// Standard error of the mean of m (as if its entries were independent).
BlockingLevel level_error(const std::vector<double>& m, std::size_t block_size) {
  BlockingLevel l;
  l.block_size = block_size;
  l.n_blocks = m.size();
  double mean = 0.0;
  for (double v : m) mean += v;
  mean /= double(m.size());
  double ss = 0.0;
  for (double v : m) ss += (v - mean) * (v - mean);
  const double nb = double(m.size());
  l.error = std::sqrt(ss / nb / (nb - 1.0));
  l.error_of_error = l.error / std::sqrt(2.0 * (nb - 1.0));
  return l;
}
}  // namespace

BlockAverage block_average(std::span<const double> x, const BlockingOptions& options) {
  options.validate();
  BlockAverage r;
  r.n = x.size();
  if (x.empty()) return r;
  double sum = 0.0;
  for (double v : x) sum += v;
  r.mean = sum / double(x.size());
  if (x.size() < 2) return r;

  std::vector<double> m(x.begin(), x.end());
  for (std::size_t block = 1; m.size() >= 2; block *= 2) {
    r.levels.push_back(level_error(m, block));
    for (std::size_t i = 0; i + 1 < m.size(); i += 2) m[i / 2] = 0.5 * (m[i] + m[i + 1]);
    m.resize(m.size() / 2);
  }
  r.naive_error = r.levels[0].error;

  // Lee et al.: smallest B with B^3 > 2 n (error_B / error_1)^4, among levels with enough
  // blocks; otherwise the last such level, flagged as no plateau. A constant series (zero
  // error everywhere) is on its plateau at B = 1.
  const double n = double(x.size()), e1 = r.levels[0].error;
  const BlockingLevel* chosen = nullptr;
  for (const BlockingLevel& l : r.levels) {
    if (l.n_blocks < options.min_blocks) break;
    chosen = &l;
    const double ratio = e1 > 0.0 ? l.error / e1 : 1.0;
    const double b = double(l.block_size);
    if (e1 == 0.0 || b * b * b > 2.0 * n * std::pow(ratio, 4)) {
      r.plateau = true;
      break;
    }
  }
  if (!chosen) chosen = &r.levels[0];  // fewer than min_blocks samples: level 0, no plateau
  r.error = chosen->error;
  r.error_of_error = chosen->error_of_error;
  r.block_size = chosen->block_size;
  r.n_blocks = chosen->n_blocks;
  return r;
}

BlockAverage block_average_tail(std::span<const double> x, double fraction,
                                const BlockingOptions& options) {
  if (!(fraction > 0.0 && fraction <= 1.0))
    fail_input("block average: fraction = ", fraction, " must be in (0, 1]");
  const std::size_t keep = std::size_t(std::floor(fraction * double(x.size())));
  return block_average(x.subspan(x.size() - keep), options);
}

}  // namespace invasim
