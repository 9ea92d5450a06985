#pragma once
// The pair terms of the contact kernel for its two drivers: the full-row gather
// (contact_force.cpp: row_terms) and the half-row scatter (contact_half.cpp: stream_terms),
// both on any number of threads. The two loops compute every pair term with the same
// expressions, so that the terms are the same bits in both (docs/performance.md, "Half rows";
// test unit_contact_half).
// Translation units including it need -fno-math-errno (CMakeLists.txt), or the square root
// keeps a scalar call and the loop does not vectorise.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "core/box.hpp"
#include "forces/contact_pairs.hpp"

namespace invasim::contact_detail {

// The constants of pair (i, j) on the branch of separation^2 r2 (repulsive unless the pair is
// cohesive and r2 > rb2), with the pair's cutoff^2 and coincidence threshold^2.
struct PairBranch {
  double rc2, tiny2, c, d, r0, e0;
};

// Vector lanes of the pair loop: 8 doubles fill an AVX-512 register (two AVX2 ones).
constexpr int kLanes = 8;

// Per-thread scratch: the contribution of every entry of one row (zero beyond the cutoff),
// and the entries' class-pair constants looked up ahead of the pair loop (look_up_pairs).
struct RowScratch {
  std::vector<int> idx, ii;     // the entries' partners j and (streams) sites i
  std::vector<int> pair_class;  // the entries' class pairs (look_up_pairs)
  std::vector<double> fx, fy, fz, e, wx, wy, wz;
  std::vector<double> rc2, rb2, tiny2, c_rep, d_rep, r0_rep, c_att, d_att, r0_att, e0;
  void reserve(std::size_t m) {
    m = (m + kLanes - 1) / kLanes * kLanes;
    if (idx.size() < m) idx.resize(m);
    if (ii.size() < m) ii.resize(m);
    if (pair_class.size() < m) pair_class.resize(m);
    for (auto* v : {&fx, &fy, &fz, &e, &wx, &wy, &wz, &rc2, &rb2, &tiny2, &c_rep, &d_rep, &r0_rep,
                    &c_att, &d_att, &r0_att, &e0})
      if (v->size() < m) v->resize(m);
  }
};

#if defined(__AVX512F__)
using LookupVector = double __attribute__((vector_size(64)));
using LookupIndex = std::int64_t __attribute__((vector_size(64)));
using LookupIndex32 = std::int32_t __attribute__((vector_size(32)));
static_assert(kLanes == 8 && PairTable::kLookupEntries == 16, "one permute of two registers");
#endif

// The class-pair constants of entries [0, m_pad) (m_pad a multiple of kLanes; entry k of class
// pair b.pair_class[k]) copied from the table into the scratch, so that the pair loop loads
// them as contiguous vectors (a gather per pair and field, which GCC emits as scalar loads, was
// ~9 % of a paper-size production). With AVX-512 and at most PairTable::kLookupEntries class
// pairs, a field of kLanes entries is one permute of the field's 16 entries held in two
// registers; otherwise one load per entry. The values are the table's either way.
template <bool kCohesive, bool kEnergy>
void look_up_pairs(const PairTable& t, int m_pad, RowScratch& b) {
  // The fields the pair loop reads (LookedUp::branch): the repulsive branch's force, the
  // attractive branch's (cohesive pairs), the energy's.
  const double* const all_from[] = {t.rc2.data(), t.tiny2.data(), t.c_rep.data(), t.d_rep.data(),
                                    t.rb2.data(), t.c_att.data(), t.d_att.data(), t.r0_rep.data(),
                                    t.e0.data(),  t.r0_att.data()};
  double* const all_to[] = {b.rc2.data(), b.tiny2.data(), b.c_rep.data(), b.d_rep.data(),
                            b.rb2.data(), b.c_att.data(), b.d_att.data(), b.r0_rep.data(),
                            b.e0.data(),  b.r0_att.data()};
  constexpr int kUsed[] = {1,         1,         1,       1,       kCohesive,
                           kCohesive, kCohesive, kEnergy, kEnergy, kCohesive && kEnergy};
  constexpr int kFields = [&] {
    int n = 0;
    for (int u : kUsed) n += u;
    return n;
  }();
  const double* from[kFields];
  double* to[kFields];
  for (int f = 0, n = 0; f < 10; ++f)
    if (kUsed[f]) {
      from[n] = all_from[f];
      to[n++] = all_to[f];
    }
  const int* __restrict cp = b.pair_class.data();
#if defined(__AVX512F__)
  if (t.n_classes() * t.n_classes() <= PairTable::kLookupEntries) {
    LookupVector lo[kFields], hi[kFields];  // each field's 16 entries, in registers
    for (int f = 0; f < kFields; ++f) {
      std::memcpy(&lo[f], from[f], sizeof lo[f]);
      std::memcpy(&hi[f], from[f] + kLanes, sizeof hi[f]);
    }
    for (int k0 = 0; k0 < m_pad; k0 += kLanes) {
      LookupIndex32 at32;
      std::memcpy(&at32, cp + k0, sizeof at32);
      const LookupIndex at = __builtin_convertvector(at32, LookupIndex);
      for (int f = 0; f < kFields; ++f) {
        const LookupVector v = __builtin_shuffle(lo[f], hi[f], at);
        std::memcpy(to[f] + k0, &v, sizeof v);
      }
    }
    return;
  }
#endif
  for (int k = 0; k < m_pad; ++k)
    for (int f = 0; f < kFields; ++f) to[f][k] = from[f][cp[k]];
}

// The branch of entry k at separation^2 r2 from the constants look_up_pairs put in the
// scratch (repulsive unless the pair is cohesive and r2 > rb2).
struct LookedUp {
  const double* __restrict rc2;
  const double* __restrict rb2;
  const double* __restrict tiny2;
  const double* __restrict c_rep;
  const double* __restrict d_rep;
  const double* __restrict r0_rep;
  const double* __restrict c_att;
  const double* __restrict d_att;
  const double* __restrict r0_att;
  const double* __restrict e0;
  explicit LookedUp(const RowScratch& b)
      : rc2(b.rc2.data()),
        rb2(b.rb2.data()),
        tiny2(b.tiny2.data()),
        c_rep(b.c_rep.data()),
        d_rep(b.d_rep.data()),
        r0_rep(b.r0_rep.data()),
        c_att(b.c_att.data()),
        d_att(b.d_att.data()),
        r0_att(b.r0_att.data()),
        e0(b.e0.data()) {}
  template <bool kCohesive>
  [[gnu::always_inline]] PairBranch branch(int k, double r2) const {
    const bool rep = !kCohesive || r2 <= rb2[k];
    const double cr = c_rep[k], ca = c_att[k], dr = d_rep[k], da = d_att[k];
    const double r0r = r0_rep[k], r0a = r0_att[k], e = e0[k];
    return {rc2[k], tiny2[k], rep ? cr : ca, rep ? dr : da, rep ? r0r : r0a, rep ? e : 0.0};
  }
};

// The constants of row i's pairs from the class table (few distinct (kind, diameter)), looked
// up for the whole row ahead of the pair loop.
struct TablePairs {
  const PairTable& t;
  int row;  // class of site i times the number of classes
  LookedUp got;
  template <bool kCohesive, bool kEnergy>
  void look_up(const int* idx, int m_pad, RowScratch& b) const {
    int* __restrict cp = b.pair_class.data();
    const int* cls = t.site_class();
#pragma omp simd
    for (int k = 0; k < m_pad; ++k) cp[k] = row + cls[idx[k]];
    look_up_pairs<kCohesive, kEnergy>(t, m_pad, b);
  }
  template <bool kCohesive>
  [[gnu::always_inline]] PairBranch branch(int k, int /*j*/, double r2) const {
    return got.branch<kCohesive>(k, r2);
  }
};

// The same constants for a stream of pairs of several rows, whose class pairs the caller put
// in b.pair_class (contact_half.cpp: from the plan, HalfRowsPlan::pair_class).
struct TableStreamPairs {
  const PairTable& t;
  LookedUp got;
  template <bool kCohesive, bool kEnergy>
  void look_up(const int* /*ii*/, const int* /*idx*/, int m_pad, RowScratch& b) const {
    look_up_pairs<kCohesive, kEnergy>(t, m_pad, b);
  }
  template <bool kCohesive>
  [[gnu::always_inline]] PairBranch branch(int k, int /*i*/, int /*j*/, double r2) const {
    return got.branch<kCohesive>(k, r2);
  }
};

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
  template <bool kCohesive, bool kEnergy>
  void look_up(const int* /*idx*/, int /*m_pad*/, RowScratch& /*b*/) const {}
  template <bool kCohesive>
  PairBranch branch(int /*k*/, int j, double r2) const {
    const int kj = kind[j];
    const PairCoefficients c = kind_pair_coefficients(0.5 * (di + diam[j]), eps[kj], ki, kj, alpha,
                                                      beta, alpha_cv, beta_cv);
    return coefficient_branch<kCohesive>(c, r2);
  }
};

// The same as DirectPairs for any pairs (i, j).
struct DirectStreamPairs {
  const double* diam;
  const int* kind;
  const double* eps;  // eps[2 kind_i + kind_j]: the energies of the kind pairs
  double alpha, beta, alpha_cv, beta_cv;
  template <bool kCohesive, bool kEnergy>
  void look_up(const int* /*ii*/, const int* /*idx*/, int /*m_pad*/, RowScratch& /*b*/) const {}
  template <bool kCohesive>
  PairBranch branch(int /*k*/, int i, int j, double r2) const {
    const int ki = kind[i], kj = kind[j];
    const PairCoefficients c = kind_pair_coefficients(0.5 * (diam[i] + diam[j]), eps[2 * ki + kj],
                                                      ki, kj, alpha, beta, alpha_cv, beta_cv);
    return coefficient_branch<kCohesive>(c, r2);
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
  pairs.template look_up<kCohesive, kEnergy>(idx, m_pad, b);
  for (int k0 = 0; k0 < m_pad; k0 += kLanes) {
#pragma omp simd
    for (int k = k0; k < k0 + kLanes; ++k) {
      const int j = idx[k];
      const double dx = wrap(xi - pos[3 * j], hx, lx), dy = wrap(yi - pos[3 * j + 1], hy, ly),
                   dz = wrap(zi - pos[3 * j + 2], hz, lz);
      const double r2 = dx * dx + dy * dy + dz * dz;
      pair_term<kEnergy, kVirial>(i, j, dx, dy, dz, r2, pairs.template branch<kCohesive>(k, j, r2),
                                  k, out);
    }
  }
}

// The pair terms of a stream of pairs (site_of(k), b.idx[k]), k < m_pad (a multiple of
// kLanes, padded with pairs (i, i); site_of(k) is b.ii[k]), into entry k of the scratch: row_terms'
// loop with site i and its constants looked up per pair (TableStreamPairs, DirectStreamPairs), the
// same operations on the same values, so the same bits (test unit_contact_half). The two loops are
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
  pairs.template look_up<kCohesive, kEnergy>(b.ii.data(), idx, m_pad, b);
  for (int k0 = 0; k0 < m_pad; k0 += kLanes) {
#pragma omp simd
    for (int k = k0; k < k0 + kLanes; ++k) {
      const int i = site_of(k), j = idx[k];
      const double xi = pos[3 * i], yi = pos[3 * i + 1], zi = pos[3 * i + 2];
      const double dx = wrap(xi - pos[3 * j], hx, lx), dy = wrap(yi - pos[3 * j + 1], hy, ly),
                   dz = wrap(zi - pos[3 * j + 2], hz, lz);
      const double r2 = dx * dx + dy * dy + dz * dz;
      pair_term<kEnergy, kVirial>(i, j, dx, dy, dz, r2,
                                  pairs.template branch<kCohesive>(k, i, j, r2), k, out);
    }
  }
}

}  // namespace invasim::contact_detail
