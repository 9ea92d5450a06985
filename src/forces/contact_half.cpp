#include "forces/contact_half.hpp"

#include <algorithm>

#include "forces/contact_force.hpp"
#include "forces/contact_kernel.hpp"

namespace invasim {

namespace {

using contact_detail::kLanes;
using contact_detail::RowScratch;

// Pairs per batch: the suffixes of consecutive rows are computed together, so that the vector
// lanes are padded once per batch instead of once per row (half rows hold ~6-8 entries).
constexpr int kBatchPairs = 512;

// Number of entries of the sorted row nb[0..m) below i (the start of the suffix j > i).
inline int lower_entries(const int* nb, int m, int i) {
  int lo = 0;
  for (int k = 0; k < m; ++k) lo += nb[k] < i;
  return lo;
}

// Rows 0..n-1 in order, in batches: the suffixes (j > i) of a batch's rows are computed into
// the scratch as one stream of pairs, then each row's terms are added to its site's
// accumulator (sequentially, in row order) and subtracted from each partner's.
template <bool kCohesive, bool kEnergy, bool kVirial, class Pairs>
void half_rows(std::size_t n, const double* pos, const VerletList& list, const MinimumImage& image,
               const Pairs& pairs, Vec3* __restrict sums, Vec3* __restrict force,
               double* __restrict site_energy, Vec3* __restrict site_virial) {
  RowScratch b;
  b.reserve(std::size_t(kBatchPairs) + list.max_count() + kLanes);
  std::vector<int> start;  // the batch's rows' first entries (and the end)
  const double* __restrict gx = b.fx.data();
  const double* __restrict gy = b.fy.data();
  const double* __restrict gz = b.fz.data();
  const double* __restrict ge = b.e.data();
  const double* __restrict wx = b.wx.data();
  const double* __restrict wy = b.wy.data();
  const double* __restrict wz = b.wz.data();
  int* __restrict idx = b.idx.data();
  int* __restrict ii = b.ii.data();
  std::size_t row = 0;
  while (row < n) {
    const std::size_t first = row;
    start.clear();
    int m = 0;
    for (; row < n && m < kBatchPairs; ++row) {
      const int* nb = list.neighbors(row);
      const int count = list.count(row);
      const int lo = lower_entries(nb, count, int(row));
      start.push_back(m);
      for (int k = lo; k < count; ++k, ++m) {
        idx[m] = nb[k];
        ii[m] = int(row);
      }
    }
    start.push_back(m);
    const int m_pad = (m + kLanes - 1) / kLanes * kLanes;
    for (int k = m; k < m_pad; ++k) idx[k] = ii[k] = int(row - 1);  // j = i: masked out
    contact_detail::stream_terms<kCohesive, kEnergy, kVirial>([ii](int k) { return ii[k]; }, m_pad,
                                                              pos, image, pairs, b);
    for (std::size_t r = first; r < row; ++r) {
      const int k0 = start[r - first], k1 = start[r - first + 1];
      double fx = sums[r][0], fy = sums[r][1], fz = sums[r][2];
      for (int k = k0; k < k1; ++k) {
        const int j = idx[k];
        fx += gx[k];
        fy += gy[k];
        fz += gz[k];
        sums[j][0] -= gx[k];
        sums[j][1] -= gy[k];
        sums[j][2] -= gz[k];
      }
      force[r] += Vec3(fx, fy, fz);
      if constexpr (kEnergy) {
        double e = site_energy[r];
        for (int k = k0; k < k1; ++k) {
          e += ge[k];
          site_energy[idx[k]] += ge[k];
        }
        site_energy[r] = e;
      }
      if constexpr (kVirial) {
        double ax = site_virial[r][0], ay = site_virial[r][1], az = site_virial[r][2];
        for (int k = k0; k < k1; ++k) {
          const int j = idx[k];
          ax += wx[k];
          ay += wy[k];
          az += wz[k];
          site_virial[j][0] += wx[k];
          site_virial[j][1] += wy[k];
          site_virial[j][2] += wz[k];
        }
        site_virial[r] = Vec3(ax, ay, az);
      }
    }
  }
}

}  // namespace

template <bool kCohesive, bool kEnergy, bool kVirial>
void contact_half_rows(System& sys, const VerletList& list, const PairTable& table,
                       const ContactParams& params, std::vector<Vec3>& sums, double* site_energy,
                       Vec3* site_virial) {
  Sites& s = sys.sites();
  const std::size_t n = s.size();
  const MinimumImage image(sys.box());
  static_assert(sizeof(Vec3) == 3 * sizeof(double), "positions are read as a flat array");
  const double* pos = s.pos.data()->data();
  sums.assign(n, Vec3::Zero());
  if (table.usable()) {
    const contact_detail::TableStreamPairs pairs{table};
    half_rows<kCohesive, kEnergy, kVirial>(n, pos, list, image, pairs, sums.data(), s.force.data(),
                                           site_energy, site_virial);
  } else {
    const double eps[4] = {params.eps_cc, params.eps_cv, params.eps_cv, params.eps_vv};
    const contact_detail::DirectStreamPairs pairs{s.diameter.data(), table.site_kind(), eps,
                                                  params.alpha, params.beta};
    half_rows<kCohesive, kEnergy, kVirial>(n, pos, list, image, pairs, sums.data(), s.force.data(),
                                           site_energy, site_virial);
  }
}

#define INVASIM_HALF_ROWS(C, E, V)                                                            \
  template void contact_half_rows<C, E, V>(System&, const VerletList&, const PairTable&,      \
                                           const ContactParams&, std::vector<Vec3>&, double*, \
                                           Vec3*);
INVASIM_HALF_ROWS(false, false, false)
INVASIM_HALF_ROWS(false, false, true)
INVASIM_HALF_ROWS(false, true, false)
INVASIM_HALF_ROWS(false, true, true)
INVASIM_HALF_ROWS(true, false, false)
INVASIM_HALF_ROWS(true, false, true)
INVASIM_HALF_ROWS(true, true, false)
INVASIM_HALF_ROWS(true, true, true)
#undef INVASIM_HALF_ROWS

}  // namespace invasim
