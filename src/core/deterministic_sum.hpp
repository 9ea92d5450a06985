#pragma once
// Sums per-site contributions in an order that does not depend on the number of OpenMP
// threads: fixed-size blocks summed in parallel, then the block sums in sequence. Any global
// quantity that feeds back into the dynamics (wall force, FIRE power) must be reduced this way.
#include <algorithm>
#include <cstddef>
#include <vector>

#include "core/parallel.hpp"
#include "core/team_barrier.hpp"

namespace invasim {

constexpr std::size_t kSumBlock = 512;

// Number of blocks of n items (the size of team_deterministic_sum's scratch).
inline std::size_t sum_blocks(std::size_t n) {
  return (n + kSumBlock - 1) / kSumBlock;
}

// The team form, for use inside a parallel region: called by every thread of the team, it
// shares the blocks with an orphaned `omp for` and returns the total in every thread (each adds
// the block sums itself, in order: no second barrier). `partial` is shared scratch sized to
// sum_blocks(n) before the region; it must not be written again before the team has passed
// another barrier (every thread reads all of it after the one inside). value(i)
// may also do per-item work (each item is visited once, in its block). Same operations in the
// same order as deterministic_sum, so both give the same bits.
template <typename T, typename F>
T team_deterministic_sum(std::size_t n, const T& zero, std::vector<T>& partial, F value) {
  const std::size_t blocks = sum_blocks(n);
#pragma omp for schedule(static) nowait
  for (std::size_t b = 0; b < blocks; ++b) {
    T s = zero;
    const std::size_t end = std::min(n, (b + 1) * kSumBlock);
    for (std::size_t i = b * kSumBlock; i < end; ++i) s += value(i);
    partial[b] = s;
  }
  team_barrier();
  T total = zero;
  for (std::size_t b = 0; b < blocks; ++b) total += partial[b];
  return total;
}

// deterministic_sum on the calling thread only (for a team's leader summing a few items).
template <typename T, typename F>
T block_sum(std::size_t n, const T& zero, F value) {
  T total = zero;
  for (std::size_t b = 0; b < sum_blocks(n); ++b) {
    T s = zero;
    const std::size_t end = std::min(n, (b + 1) * kSumBlock);
    for (std::size_t i = b * kSumBlock; i < end; ++i) s += value(i);
    total += s;
  }
  return total;
}

// Sum of value(i) for i in [0, n), starting from zero (pass T's zero: 0.0, Vec3::Zero()).
template <typename T, typename F>
T deterministic_sum(std::size_t n, const T& zero, F value) {
  if (!parallel_light(n)) return block_sum(n, zero, value);
  std::vector<T> partial(sum_blocks(n), zero);
  T total = zero;
#pragma omp parallel if (parallel_light(n))
  {
    const T t = team_deterministic_sum(n, zero, partial, value);
    if (team_leader()) total = t;
  }
  return total;
}

}  // namespace invasim
