#pragma once
// The drift's half kick, move and zeroed force for blocks of 8 consecutive sites in AVX-512
// lanes (drift_range in dynamics.cpp). A block's 24 velocity, position and force components
// are three whole vectors; each site's h = (dt / 2) / m is spread over its three components by
// a permutation, and the wrap test's bounds repeat with period 3 over the block. GCC left the
// per-site loop (a stride-3 inner loop with the wrap test) scalar. The same operations as the
// scalar loop, one rounding per fused multiply-add (core/fused.hpp), so the same bits. Only
// with AVX-512 F: INVASIM_DRIFT_LANES says whether it is compiled.
#include <limits>

#include "core/box.hpp"

#if defined(__AVX512F__) && defined(__FP_FAST_FMA)
#include <immintrin.h>
#define INVASIM_DRIFT_LANES 1
#else
#define INVASIM_DRIFT_LANES 0
#endif

namespace invasim::integrate_detail {

// Bounds of the drift's wrap test: the box on a periodic axis, +-inf on a walled one (never
// wraps); per axis, and repeated over a block's 24 components (component e is axis e mod 3),
// made once per list of slots that the drift moves.
struct WrapBounds {
  double lo[3], hi[3];
  alignas(64) double block_lo[24], block_hi[24];
  explicit WrapBounds(const Box& box) {
    for (int a = 0; a < 3; ++a) {
      const bool p = box.periodic(a);
      lo[a] = p ? box.lo()[a] : -std::numeric_limits<double>::infinity();
      hi[a] = p ? box.hi()[a] : std::numeric_limits<double>::infinity();
    }
    for (int e = 0; e < 24; ++e) {
      block_lo[e] = lo[e % 3];
      block_hi[e] = hi[e % 3];
    }
  }
};

#if INVASIM_DRIFT_LANES
// Drifts the whole blocks of 8 sites from `lo` on (flat arrays of 3 components per site, masses
// m) and returns the first site not drifted (lo + a multiple of 8, at most hi). Sets `outside`
// to 1 if a new position is not within the bounds on some axis (a NaN counts as outside).
inline int drift_blocks_lanes(double* __restrict v, double* __restrict x, double* __restrict f,
                              const double* __restrict m, const WrapBounds& bounds, int lo, int hi,
                              double dt, int& outside) {
  // Vector q of a block holds its components 8q .. 8q+7.
  const double *blo = bounds.block_lo, *bhi = bounds.block_hi;
  const __m512i site_of[3] = {_mm512_setr_epi64(0, 0, 0, 1, 1, 1, 2, 2),
                              _mm512_setr_epi64(2, 3, 3, 3, 4, 4, 4, 5),
                              _mm512_setr_epi64(5, 5, 6, 6, 6, 7, 7, 7)};
  const __m512d half_dt = _mm512_set1_pd(0.5 * dt), step = _mm512_set1_pd(dt);
  const __m512d zero = _mm512_setzero_pd();
  __mmask8 out = 0;
  int i = lo;
  for (; i + 8 <= hi; i += 8) {
    const __m512d h = _mm512_div_pd(half_dt, _mm512_loadu_pd(m + i));
    for (int q = 0; q < 3; ++q) {
      const int k = 3 * i + 8 * q;
      // (The zero-masked form: GCC 12 warns about the unmasked one's undefined source.)
      const __m512d hq = _mm512_maskz_permutexvar_pd(0xFF, site_of[q], h);
      const __m512d vel = _mm512_fmadd_pd(hq, _mm512_loadu_pd(f + k), _mm512_loadu_pd(v + k));
      const __m512d pos = _mm512_fmadd_pd(step, vel, _mm512_loadu_pd(x + k));
      _mm512_storeu_pd(v + k, vel);
      _mm512_storeu_pd(x + k, pos);
      _mm512_storeu_pd(f + k, zero);
      out |= _mm512_cmp_pd_mask(pos, _mm512_load_pd(blo + 8 * q), _CMP_NGE_UQ) |
             _mm512_cmp_pd_mask(pos, _mm512_load_pd(bhi + 8 * q), _CMP_NLT_UQ);
    }
  }
  if (out) outside = 1;
  return i;
}
#endif

}  // namespace invasim::integrate_detail
