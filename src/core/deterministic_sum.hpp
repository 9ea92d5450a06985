#pragma once
// Sums per-site contributions in an order that does not depend on the number of OpenMP
// threads: fixed-size blocks summed in parallel, then the block sums in sequence. Any global
// quantity that feeds back into the dynamics (wall force, FIRE power) must be reduced this way.
#include <algorithm>
#include <cstddef>
#include <vector>

#include "core/parallel.hpp"

namespace invasim {

constexpr std::size_t kSumBlock = 512;

// Sum of value(i) for i in [0, n), starting from zero (pass T's zero: 0.0, Vec3::Zero()).
template <typename T, typename F>
T deterministic_sum(std::size_t n, const T& zero, F value) {
  const std::size_t blocks = (n + kSumBlock - 1) / kSumBlock;
  std::vector<T> partial(blocks, zero);
#pragma omp parallel for schedule(static) if (parallel_light(n))
  for (std::size_t b = 0; b < blocks; ++b) {
    T s = zero;
    const std::size_t end = std::min(n, (b + 1) * kSumBlock);
    for (std::size_t i = b * kSumBlock; i < end; ++i) s += value(i);
    partial[b] = s;
  }
  T total = zero;
  for (const T& s : partial) total += s;
  return total;
}

}  // namespace invasim
