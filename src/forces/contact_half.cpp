#include "forces/contact_half.hpp"

#include "forces/contact_force.hpp"
#include "forces/contact_kernel.hpp"

namespace invasim {

namespace {

using contact_detail::RowScratch;

// Number of entries of the sorted row nb[0..m) below i (the start of the suffix j > i).
inline int lower_entries(const int* nb, int m, int i) {
  int lo = 0;
  for (int k = 0; k < m; ++k) lo += nb[k] < i;
  return lo;
}

// Rows 0..n-1 in order: the suffix of row i into the scratch, then its terms added to site
// i's accumulator (sequentially, row order) and subtracted from each partner's.
template <bool kCohesive, bool kEnergy, bool kVirial, class PairsOf>
void half_rows(std::size_t n, const double* pos, const VerletList& list, const MinimumImage& image,
               const PairsOf& pairs_of, Vec3* __restrict sums, Vec3* __restrict force,
               double* __restrict site_energy, Vec3* __restrict site_virial) {
  RowScratch b;
  b.reserve(list.max_count());
  const double* __restrict gx = b.fx.data();
  const double* __restrict gy = b.fy.data();
  const double* __restrict gz = b.fz.data();
  const double* __restrict ge = b.e.data();
  const double* __restrict wx = b.wx.data();
  const double* __restrict wy = b.wy.data();
  const double* __restrict wz = b.wz.data();
  for (std::size_t ii = 0; ii < n; ++ii) {
    const int i = int(ii);
    const int* nb = list.neighbors(ii);
    const int m = list.count(ii);
    const int lo = lower_entries(nb, m, i);
    const int* up = nb + lo;
    const int mh = m - lo;
    contact_detail::row_terms<kCohesive, kEnergy, kVirial>(i, pos, up, mh, image, pairs_of(i), b);
    double fx = sums[ii][0], fy = sums[ii][1], fz = sums[ii][2];
    for (int k = 0; k < mh; ++k) {
      const int j = up[k];
      fx += gx[k];
      fy += gy[k];
      fz += gz[k];
      sums[j][0] -= gx[k];
      sums[j][1] -= gy[k];
      sums[j][2] -= gz[k];
    }
    force[ii] += Vec3(fx, fy, fz);
    if constexpr (kEnergy) {
      double e = site_energy[ii];
      for (int k = 0; k < mh; ++k) {
        e += ge[k];
        site_energy[up[k]] += ge[k];
      }
      site_energy[ii] = e;
    }
    if constexpr (kVirial) {
      double ax = site_virial[ii][0], ay = site_virial[ii][1], az = site_virial[ii][2];
      for (int k = 0; k < mh; ++k) {
        const int j = up[k];
        ax += wx[k];
        ay += wy[k];
        az += wz[k];
        site_virial[j][0] += wx[k];
        site_virial[j][1] += wy[k];
        site_virial[j][2] += wz[k];
      }
      site_virial[ii] = Vec3(ax, ay, az);
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
    auto pairs_of = [&](int i) {
      return contact_detail::TablePairs{table, table.site_class(),
                                        table.site_class()[i] * table.n_classes()};
    };
    half_rows<kCohesive, kEnergy, kVirial>(n, pos, list, image, pairs_of, sums.data(),
                                           s.force.data(), site_energy, site_virial);
  } else {
    const double eps[2][2] = {{params.eps_cc, params.eps_cv}, {params.eps_cv, params.eps_vv}};
    auto pairs_of = [&](int i) {
      return contact_detail::DirectPairs{s.diameter.data(), table.site_kind(), eps[int(s.kind[i])],
                                         params.alpha,      params.beta,       s.diameter[i],
                                         int(s.kind[i])};
    };
    half_rows<kCohesive, kEnergy, kVirial>(n, pos, list, image, pairs_of, sums.data(),
                                           s.force.data(), site_energy, site_virial);
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
