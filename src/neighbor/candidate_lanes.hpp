#pragma once
// The list build's candidate test in AVX-512 lanes (VerletList::build_team): 8 candidates of a
// run at a time, the run's tail masked, and the partners kept written with one compress.
// The same arithmetic as the scalar pass (the minimum image as d - l or d + l where the
// comparisons say so, the squared distance against the pair's list radius, pairs of one body
// left out); a pair exactly at the list radius may round to the other side, which no force
// sees (the list radius is the force cutoff plus the skin). Only with AVX-512 (F and VL):
// INVASIM_CANDIDATE_LANES says whether it is compiled.
#include <algorithm>

#if defined(__AVX512F__) && defined(__AVX512VL__)
#include <immintrin.h>
#define INVASIM_CANDIDATE_LANES 1
#else
#define INVASIM_CANDIDATE_LANES 0
#endif

namespace invasim::neighbor_detail {

// A site's view of the candidates: its position, diameter and body (-1: none), the box's
// minimum-image constants (half length, length; +inf and 0 on a walled axis) and the list
// radius rule (rc = half_factor (d_i + d_j) + skin).
struct CandidateSite {
  double x, y, z, d;
  int body;
  double hx, hy, hz, lx, ly, lz;
  double half_factor, skin;
};

#if INVASIM_CANDIDATE_LANES
// One axis' separation, minimum image applied (the scalar pass's d - l [d > h] + l [d < -h]).
[[gnu::always_inline]] inline __m512d nearest_image_lanes(__m512d d, double half, double len) {
  const __m512d h = _mm512_set1_pd(half), l = _mm512_set1_pd(len);
  const __mmask8 above = _mm512_cmp_pd_mask(d, h, _CMP_GT_OQ);
  const __mmask8 below = _mm512_cmp_pd_mask(d, _mm512_sub_pd(_mm512_setzero_pd(), h), _CMP_LT_OQ);
  d = _mm512_mask_sub_pd(d, above, d, l);
  return _mm512_mask_add_pd(d, below, d, l);
}

// Tests candidates [p0, p1) (cell-order copies px, py, pz, pd, pb; their sites `sites`) and
// appends the kept ones' sites to out[m...]; returns the new count. The caller guarantees room
// for all p1 - p0 and 7 more (each group of 8 is stored whole, its kept ones first).
inline int keep_candidates_lanes(const CandidateSite& c, const double* px, const double* py,
                                 const double* pz, const double* pd, const int* pb,
                                 const int* sites, int p0, int p1, int* out, int m) {
  const __m512d xi = _mm512_set1_pd(c.x), yi = _mm512_set1_pd(c.y), zi = _mm512_set1_pd(c.z);
  const __m512d di = _mm512_set1_pd(c.d), hf = _mm512_set1_pd(c.half_factor);
  const __m512d skin = _mm512_set1_pd(c.skin);
  const __m256i body = _mm256_set1_epi32(c.body);
  for (int p = p0; p < p1; p += 8) {
    const __mmask8 lane = __mmask8((1u << std::min(8, p1 - p)) - 1u);
    const __m512d dx =
        nearest_image_lanes(_mm512_sub_pd(xi, _mm512_maskz_loadu_pd(lane, px + p)), c.hx, c.lx);
    const __m512d dy =
        nearest_image_lanes(_mm512_sub_pd(yi, _mm512_maskz_loadu_pd(lane, py + p)), c.hy, c.ly);
    const __m512d dz =
        nearest_image_lanes(_mm512_sub_pd(zi, _mm512_maskz_loadu_pd(lane, pz + p)), c.hz, c.lz);
    const __m512d r2 = _mm512_fmadd_pd(dz, dz, _mm512_fmadd_pd(dy, dy, _mm512_mul_pd(dx, dx)));
    const __m512d rc =
        _mm512_fmadd_pd(hf, _mm512_add_pd(di, _mm512_maskz_loadu_pd(lane, pd + p)), skin);
    __mmask8 keep = _mm512_mask_cmp_pd_mask(lane, r2, _mm512_mul_pd(rc, rc), _CMP_LT_OQ);
    if (c.body >= 0)
      keep = _mm256_mask_cmpneq_epi32_mask(keep, _mm256_maskz_loadu_epi32(lane, pb + p), body);
    // Compressed in a register, then stored whole (a compress-store to memory is microcoded
    // on AMD Zen 4, ~10x slower); the lanes past the kept ones write inside the row.
    _mm256_storeu_si256(
        reinterpret_cast<__m256i*>(out + m),
        _mm256_maskz_compress_epi32(keep, _mm256_maskz_loadu_epi32(lane, sites + p)));
    m += __builtin_popcount(unsigned(keep));
  }
  return m;
}
#endif

}  // namespace invasim::neighbor_detail
