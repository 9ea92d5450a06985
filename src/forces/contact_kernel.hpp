#pragma once
// The pair terms of the contact kernel for its two drivers: the full-row gather
// (contact_force.cpp: row_terms) and the half-row scatter (contact_half.cpp: stream_terms),
// both on any number of threads. The two loops compute every pair term with the same
// expressions, so that the terms are the same bits in both (docs/performance.md, "Half rows";
// test unit_contact_half).
// Translation units including it need -fno-math-errno (CMakeLists.txt), or the square root
// keeps a scalar call and the loop does not vectorise.
#include <cmath>
#include <vector>

#include "core/box.hpp"
#include "forces/contact_pairs.hpp"

namespace invasim::contact_detail {

// The constants of pair (i, j) on the branch of separation^2 r2 (repulsive unless the pair is
// cohesive and r2 > rb2), with the pair's cutoff^2 and coincidence threshold^2.
struct PairBranch {
  double rc2, tiny2, c, d, r0, e0;
};

// The branch of class pair k at separation^2 r2 (both class-table lookups).
template <bool kCohesive>
[[gnu::always_inline]] inline PairBranch table_branch(const PairTable& t, int k, double r2) {
  const bool rep = !kCohesive || r2 <= t.rb2[k];
  const int b = 2 * k + (rep ? 0 : 1);
  return {t.rc2[k], t.tiny2[k], t.c[b], t.d[b], t.r0[b], t.e0[b]};
}

// The branch of a pair's coefficients at separation^2 r2 (both direct lookups).
template <bool kCohesive>
[[gnu::always_inline]] inline PairBranch coefficient_branch(const PairCoefficients& c, double r2) {
  const bool rep = !kCohesive || r2 <= c.rb2;
  return {c.rc2,
          c.tiny2,
          rep ? c.c_rep : c.c_att,
          rep ? c.d_rep : c.d_att,
          rep ? c.r0_rep : c.r0_att,
          rep ? c.e0 : 0.0};
}

// The constants of pair (i, j) read from the class table (few distinct (kind, diameter)); the
// branch's constants are loaded at a computed index (see PairTable).
struct TablePairs {
  const PairTable& t;
  const int* cls;
  int row;  // class of site i times the number of classes
  template <bool kCohesive>
  PairBranch branch(int j, double r2) const {
    return table_branch<kCohesive>(t, row + cls[j], r2);
  }
};

// The constants of a pair of site kinds ki, kj (0: cancer, 1: vertex): cohesion between two
// cancer cells, adhesion between a cancer cell and a vertex, none between vertices (the same
// choice as ContactParams::pair_alpha / pair_beta, in plain values for the vector lanes).
[[gnu::always_inline]] inline PairCoefficients kind_pair_coefficients(double s, double eps, int ki,
                                                                      int kj, double alpha,
                                                                      double beta, double alpha_cv,
                                                                      double beta_cv) {
  const bool cc = (ki | kj) == 0, cv = ki != kj;
  return pair_coefficients(s, eps, cv ? alpha_cv : alpha, cc ? beta : (cv ? beta_cv : 0.0));
}

// The constants of pair (i, j) computed from the diameters (fallback for many classes).
struct DirectPairs {
  const double* diam;
  const int* kind;
  const double* eps;  // the energies of site i's kind with kinds 0 and 1
  double alpha, beta, alpha_cv, beta_cv, di;
  int ki;
  template <bool kCohesive>
  PairBranch branch(int j, double r2) const {
    const int kj = kind[j];
    const PairCoefficients c = kind_pair_coefficients(0.5 * (di + diam[j]), eps[kj], ki, kj, alpha,
                                                      beta, alpha_cv, beta_cv);
    return coefficient_branch<kCohesive>(c, r2);
  }
};

// The same constants for any pairs (i, j) (a stream of pairs of several rows): the class
// pair or site i's kind and diameter looked up per pair.
struct TableStreamPairs {
  const PairTable& t;
  template <bool kCohesive>
  PairBranch branch(int i, int j, double r2) const {
    const int* cls = t.site_class();
    return table_branch<kCohesive>(t, cls[i] * t.n_classes() + cls[j], r2);
  }
};

// The same as DirectPairs for any pairs (i, j).
struct DirectStreamPairs {
  const double* diam;
  const int* kind;
  const double* eps;  // eps[2 kind_i + kind_j]: the energies of the kind pairs
  double alpha, beta, alpha_cv, beta_cv;
  template <bool kCohesive>
  PairBranch branch(int i, int j, double r2) const {
    const int ki = kind[i], kj = kind[j];
    const PairCoefficients c = kind_pair_coefficients(0.5 * (diam[i] + diam[j]), eps[2 * ki + kj],
                                                      ki, kj, alpha, beta, alpha_cv, beta_cv);
    return coefficient_branch<kCohesive>(c, r2);
  }
};

// Vector lanes of the pair loop: 8 doubles fill an AVX-512 register (two AVX2 ones).
constexpr int kLanes = 8;

// Per-thread scratch: the contribution of every entry of one row (zero beyond the cutoff).
struct RowScratch {
  std::vector<int> idx, ii;  // the entries' partners j and (streams) sites i
  std::vector<double> fx, fy, fz, e, wx, wy, wz;
  void reserve(std::size_t m) {
    m = (m + kLanes - 1) / kLanes * kLanes;
    if (idx.size() < m) idx.resize(m);
    if (ii.size() < m) ii.resize(m);
    for (auto* v : {&fx, &fy, &fz, &e, &wx, &wy, &wz})
      if (v->size() < m) v->resize(m);
  }
};

// Where pair_term writes entry k's terms (the scratch's arrays).
struct TermOut {
  double* __restrict gx;
  double* __restrict gy;
  double* __restrict gz;
  double* __restrict ge;
  double* __restrict wx;
  double* __restrict wy;
  double* __restrict wz;
};

// The terms of pair (i, j) at separation (dx, dy, dz) = x_i - x_j (minimum image), r2 its
// square, c its branch's constants, into entry k: the force on i (zero beyond the cutoff and
// for j == i), half the pair energy, half the pair virial. The one expression of the pair law
// for both drivers' loops (row_terms, stream_terms), so that their terms are the same bits;
// always inlined, so that each loop still vectorises as a whole.
template <bool kEnergy, bool kVirial>
[[gnu::always_inline]] inline void pair_term(int i, int j, double dx, double dy, double dz,
                                             double r2, const PairBranch c, int k,
                                             const TermOut& o) {
  const bool in = r2 < c.rc2 && j != i;
  const double cf = c.c, df = c.d;
  const double r = std::sqrt(r2);
  const double inv_r = 1.0 / r;
  // Coincident sites: the force at r along a fixed direction, opposite for the partners.
  const bool coincident = r2 <= c.tiny2;
  const double f_over_r = cf * inv_r - df;
  const double sign = i < j ? 1.0 : -1.0;
  const double fx = coincident ? (cf - df * r) * sign : f_over_r * dx;
  const double fy = coincident ? 0.0 : f_over_r * dy;
  const double fz = coincident ? 0.0 : f_over_r * dz;
  o.gx[k] = in ? fx : 0.0;
  o.gy[k] = in ? fy : 0.0;
  o.gz[k] = in ? fz : 0.0;
  if constexpr (kEnergy) {
    const double u = 0.5 * df * (r - c.r0) * (r - c.r0) + c.e0;
    o.ge[k] = in ? 0.5 * u : 0.0;
  }
  if constexpr (kVirial) {
    o.wx[k] = in ? 0.5 * fx * dx : 0.0;
    o.wy[k] = in ? 0.5 * fy * dy : 0.0;
    o.wz[k] = in ? 0.5 * fz * dz : 0.0;
  }
}

// The pair terms of site i with the sites nb[0..m) into the scratch (entry k: the force on i
// from nb[k], half the pair energy, half the pair virial; zero beyond the cutoff), computed
// in a vectorisable loop. The term of (j, i) is bitwise minus the term of (i, j) for the force
// and the same for energy and virial: dx = wrap(xi - xj) is exactly antisymmetric, r2, the
// class-pair constants and f/r are symmetric, and coincident sites take `sign` from i < j.
template <bool kCohesive, bool kEnergy, bool kVirial, class Pairs>
void row_terms(int i, const double* pos, const int* nb, int m, const MinimumImage& image,
               const Pairs& pairs, RowScratch& b) {
  const double xi = pos[3 * i], yi = pos[3 * i + 1], zi = pos[3 * i + 2];
  // The minimum image with the box's constants in registers.
  const double hx = image.half(0), hy = image.half(1), hz = image.half(2);
  const double lx = image.length(0), ly = image.length(1), lz = image.length(2);
  const auto wrap = MinimumImage::wrap;
  const TermOut out{b.fx.data(), b.fy.data(), b.fz.data(), b.e.data(),
                    b.wx.data(), b.wy.data(), b.wz.data()};
  // The row padded to whole vectors with site i itself (masked out below), so that every
  // entry is computed in vector lanes (rows are short: a remainder loop would dominate).
  const int m_pad = (m + kLanes - 1) / kLanes * kLanes;
  int* __restrict idx = b.idx.data();
  for (int k = 0; k < m; ++k) idx[k] = nb[k];
  for (int k = m; k < m_pad; ++k) idx[k] = i;
  for (int k0 = 0; k0 < m_pad; k0 += kLanes) {
#pragma omp simd
    for (int k = k0; k < k0 + kLanes; ++k) {
      const int j = idx[k];
      const double dx = wrap(xi - pos[3 * j], hx, lx), dy = wrap(yi - pos[3 * j + 1], hy, ly),
                   dz = wrap(zi - pos[3 * j + 2], hz, lz);
      const double r2 = dx * dx + dy * dy + dz * dz;
      pair_term<kEnergy, kVirial>(i, j, dx, dy, dz, r2, pairs.template branch<kCohesive>(j, r2), k,
                                  out);
    }
  }
}

// The pair terms of a stream of pairs (site_of(k), b.idx[k]), k < m_pad (a multiple of
// kLanes, padded with pairs (i, i)), into entry k of the scratch: row_terms' loop with site i
// and its constants looked up per pair (TableStreamPairs, DirectStreamPairs), the same
// operations on the same values, so the same bits (test unit_contact_half). The two loops are
// separate because GCC 12 vectorised neither when one loop served both (site i broadcast for
// a row, gathered for a stream); the pair law itself is one function, pair_term (its
// constants passed by value: by reference, this loop stayed scalar). site_of must stay a
// lambda (reading b.ii directly kept this loop scalar).
template <bool kCohesive, bool kEnergy, bool kVirial, class Pairs, class SiteOf>
void stream_terms(SiteOf site_of, int m_pad, const double* pos, const MinimumImage& image,
                  const Pairs& pairs, RowScratch& b) {
  // The minimum image with the box's constants in registers.
  const double hx = image.half(0), hy = image.half(1), hz = image.half(2);
  const double lx = image.length(0), ly = image.length(1), lz = image.length(2);
  const auto wrap = MinimumImage::wrap;
  const TermOut out{b.fx.data(), b.fy.data(), b.fz.data(), b.e.data(),
                    b.wx.data(), b.wy.data(), b.wz.data()};
  const int* __restrict idx = b.idx.data();
  for (int k0 = 0; k0 < m_pad; k0 += kLanes) {
#pragma omp simd
    for (int k = k0; k < k0 + kLanes; ++k) {
      const int i = site_of(k), j = idx[k];
      const double xi = pos[3 * i], yi = pos[3 * i + 1], zi = pos[3 * i + 2];
      const double dx = wrap(xi - pos[3 * j], hx, lx), dy = wrap(yi - pos[3 * j + 1], hy, ly),
                   dz = wrap(zi - pos[3 * j + 2], hz, lz);
      const double r2 = dx * dx + dy * dy + dz * dz;
      pair_term<kEnergy, kVirial>(i, j, dx, dy, dz, r2, pairs.template branch<kCohesive>(i, j, r2),
                                  k, out);
    }
  }
}

}  // namespace invasim::contact_detail
