#include "forces/contact_half.hpp"

#include <algorithm>
#include <cmath>

#include "forces/contact_force.hpp"

namespace invasim {

namespace {

using contact_detail::kLanes;
using contact_detail::RowScratch;

// Pairs per batch: the entries of consecutive rows are computed together, so that the vector
// lanes are padded once per batch instead of once per row (half rows hold ~6-8 entries).
constexpr int kBatchPairs = 512;

// The extent of the sites along each axis: the box length on a periodic axis, else the span
// of the positions (walls), with its lower end.
struct Extent {
  double lo[3], len[3];
};
Extent site_extent(const System& sys) {
  const auto& pos = sys.sites().pos;
  Extent e{};
  for (int a = 0; a < 3; ++a) {
    if (sys.box().periodic(a)) {
      e.lo[a] = sys.box().lo()[a];
      e.len[a] = sys.box().length(a);
      continue;
    }
    double lo = pos.empty() ? 0.0 : pos[0][a], hi = lo;
    for (const Vec3& r : pos) {
      lo = std::min(lo, r[a]);
      hi = std::max(hi, r[a]);
    }
    e.lo[a] = lo;
    e.len[a] = hi - lo;
  }
  return e;
}

}  // namespace

int slab_axis(const System& sys, int parts) {
  // The axis whose cuts cross the least area: parts - 1 cuts between walls, parts cuts around
  // a periodic axis (the last slab meets the first).
  const Extent e = site_extent(sys);
  int axis = 0;
  double best = 0.0;
  for (int a = 0; a < 3; ++a) {
    const double cuts = sys.box().periodic(a) ? parts : parts - 1;
    const double area = cuts * e.len[(a + 1) % 3] * e.len[(a + 2) % 3];
    if (a == 0 || area < best) {
      best = area;
      axis = a;
    }
  }
  return axis;
}

void partition_sites(const System& sys, const VerletList& list, int parts,
                     std::vector<int>& owner) {
  const std::size_t n = sys.n_sites();
  owner.assign(n, 0);
  if (parts <= 1 || n == 0) return;
  const Extent e = site_extent(sys);
  const int axis = slab_axis(sys, parts);
  // Slabs of equal work: a histogram of the row lengths (each row's pairs are computed once,
  // its half) along the axis, cut at the quantiles.
  const int bins = int(std::clamp<std::size_t>(n / 4, 16, 4096));
  const double scale = e.len[axis] > 0.0 ? bins / e.len[axis] : 0.0;
  const auto& pos = sys.sites().pos;
  auto bin_of = [&](std::size_t i) {
    return std::clamp(int((pos[i][axis] - e.lo[axis]) * scale), 0, bins - 1);
  };
  std::vector<double> weight(std::size_t(bins), 0.0);
  double total = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double w = 1.0 + list.count(i);
    weight[std::size_t(bin_of(i))] += w;
    total += w;
  }
  std::vector<int> part_of_bin(static_cast<std::size_t>(bins));
  double before = 0.0;
  for (int b = 0; b < bins; ++b) {
    const double mid = before + 0.5 * weight[std::size_t(b)];
    part_of_bin[std::size_t(b)] = std::min(parts - 1, int(parts * mid / total));
    before += weight[std::size_t(b)];
  }
  for (std::size_t i = 0; i < n; ++i) owner[i] = part_of_bin[std::size_t(bin_of(i))];
}

void plan_half_rows(const VerletList& list, const std::vector<int>& owner, int thread,
                    std::vector<int>& rank, HalfRowsPlan& plan) {
  const std::size_t n = owner.size();
  plan.rows.clear();
  plan.owned.clear();
  plan.start.assign(1, 0);
  plan.partner.clear();
  plan.target.clear();
  plan.pair_class_table = 0;
  plan.halo.resize(n, 0);
  // This thread's sites' ranks, and the halo rows: other threads' sites i < j in the rows of
  // this thread's sites j (none when the thread owns every site).
  int n_owned = 0;
  for (std::size_t j = 0; j < n; ++j)
    if (owner[j] == thread) rank[j] = n_owned++;
  const bool owns_all = std::size_t(n_owned) == n;
  if (!owns_all)
    for (std::size_t j = 0; j < n; ++j) {
      if (owner[j] != thread) continue;
      const int* nb = list.neighbors(j);
      for (int k = 0, m = list.count(j); k < m && nb[k] < int(j); ++k)
        if (owner[std::size_t(nb[k])] != thread) plan.halo[std::size_t(nb[k])] = 1;
    }
  plan.n_owned = std::size_t(n_owned);
  for (std::size_t i = 0; i < n; ++i) {
    const bool own = owner[i] == thread;
    if (!own && !plan.halo[i]) continue;
    plan.halo[i] = 0;
    const int* nb = list.neighbors(i);
    const int m = list.count(i);
    const int lo = int(std::upper_bound(nb, nb + m, int(i)) - nb);  // the suffix j > i
    if (own) {
      // The whole suffix (copied at once), each partner's accumulator: its rank if this
      // thread's, else the spare.
      const std::size_t first = plan.partner.size();
      plan.partner.insert(plan.partner.end(), nb + lo, nb + m);
      plan.target.resize(plan.partner.size());
      int* __restrict target = plan.target.data() + first;
      for (int k = lo; k < m; ++k) {
        const std::size_t j = std::size_t(nb[k]);
        *target++ = owns_all || owner[j] == thread ? rank[j] : n_owned;
      }
    } else {
      for (int k = lo; k < m; ++k) {  // a halo row serves this thread's partners only
        const int j = nb[k];
        if (owner[std::size_t(j)] != thread) continue;
        plan.partner.push_back(j);
        plan.target.push_back(rank[std::size_t(j)]);
      }
    }
    plan.rows.push_back(int(i));
    plan.owned.push_back(own ? 1 : 0);
    plan.start.push_back(int(plan.partner.size()));
  }
}

namespace {

// The plan's rows in order, in batches: the entries of a batch's rows are computed into the
// scratch as one stream of pairs, then each owned row's terms are added to its accumulator
// (sequentially, in row order) and its force written, and every entry's term is subtracted
// from its target's accumulator.
template <bool kCohesive, bool kEnergy, bool kVirial, class Pairs>
void half_rows(HalfRowsPlan& plan, const double* pos, const MinimumImage& image, const Pairs& pairs,
               RowScratch& b, Vec3* __restrict force, double* __restrict site_energy,
               Vec3* __restrict site_virial) {
  const double* __restrict gx = b.fx.data();
  const double* __restrict gy = b.fy.data();
  const double* __restrict gz = b.fz.data();
  const double* __restrict ge = b.e.data();
  const double* __restrict wx = b.wx.data();
  const double* __restrict wy = b.wy.data();
  const double* __restrict wz = b.wz.data();
  int* __restrict idx = b.idx.data();
  int* __restrict ii = b.ii.data();
  const int* __restrict partner = plan.partner.data();
  const int* __restrict start = plan.start.data();
  // The entries' class pairs, when the constants come from the class table (empty otherwise).
  const int* __restrict pair_class = plan.pair_class.empty() ? nullptr : plan.pair_class.data();
  int* __restrict cp = b.pair_class.data();
  Vec3* __restrict sums = plan.sums.data();
  double* __restrict energy = plan.energy.data();
  Vec3* __restrict virial = plan.virial.data();
  const std::size_t n_rows = plan.rows.size();
  std::size_t row = 0;
  int rank = 0;  // of the next owned row's site
  while (row < n_rows) {
    const std::size_t first = row;
    const int base = start[first];
    int m = 0;
    for (; row < n_rows && m < kBatchPairs; ++row) {
      const int i = plan.rows[row];
      for (int k = start[row]; k < start[row + 1]; ++k, ++m) {
        idx[m] = partner[k];
        ii[m] = i;
        if (pair_class) cp[m] = pair_class[k];
      }
    }
    const int m_pad = (m + kLanes - 1) / kLanes * kLanes;
    const int last = plan.rows[row - 1];
    for (int k = m; k < m_pad; ++k) {
      idx[k] = ii[k] = last;      // j = i: masked out
      if (pair_class) cp[k] = 0;  // any class pair: the entry is masked out
    }
    contact_detail::stream_terms<kCohesive, kEnergy, kVirial>([ii](int k) { return ii[k]; }, m_pad,
                                                              pos, image, pairs, b);
    const int* __restrict to = plan.target.data() + base;
    for (std::size_t r = first; r < row; ++r) {
      const int k0 = start[r] - base, k1 = start[r + 1] - base;
      if (!plan.owned[r]) {  // a halo row: site i is another thread's, its partners are ours
        for (int k = k0; k < k1; ++k) {
          sums[to[k]][0] -= gx[k];
          sums[to[k]][1] -= gy[k];
          sums[to[k]][2] -= gz[k];
          if constexpr (kEnergy) energy[to[k]] += ge[k];
          if constexpr (kVirial) {
            virial[to[k]][0] += wx[k];
            virial[to[k]][1] += wy[k];
            virial[to[k]][2] += wz[k];
          }
        }
        continue;
      }
      const int i = plan.rows[r], me = rank++;
      double fx = sums[me][0], fy = sums[me][1], fz = sums[me][2];
      for (int k = k0; k < k1; ++k) {
        fx += gx[k];
        fy += gy[k];
        fz += gz[k];
        sums[to[k]][0] -= gx[k];
        sums[to[k]][1] -= gy[k];
        sums[to[k]][2] -= gz[k];
      }
      force[i] += Vec3(fx, fy, fz);
      if constexpr (kEnergy) {
        double e = energy[me];
        for (int k = k0; k < k1; ++k) {
          e += ge[k];
          energy[to[k]] += ge[k];
        }
        site_energy[i] = e;
      }
      if constexpr (kVirial) {
        double ax = virial[me][0], ay = virial[me][1], az = virial[me][2];
        for (int k = k0; k < k1; ++k) {
          ax += wx[k];
          ay += wy[k];
          az += wz[k];
          virial[to[k]][0] += wx[k];
          virial[to[k]][1] += wy[k];
          virial[to[k]][2] += wz[k];
        }
        site_virial[i] = Vec3(ax, ay, az);
      }
    }
  }
}

}  // namespace

template <bool kCohesive, bool kEnergy, bool kVirial>
void contact_half_rows(System& sys, HalfRowsPlan& plan, std::size_t max_count,
                       const PairTable& table, const ContactParams& params, double* site_energy,
                       Vec3* site_virial, RowScratch& scratch) {
  Sites& s = sys.sites();
  const MinimumImage image(sys.box());
  static_assert(sizeof(Vec3) == 3 * sizeof(double), "positions are read as a flat array");
  const double* pos = s.pos.data()->data();
  plan.sums.assign(plan.n_owned + 1, Vec3::Zero());
  if constexpr (kEnergy) plan.energy.assign(plan.n_owned + 1, 0.0);
  if constexpr (kVirial) plan.virial.assign(plan.n_owned + 1, Vec3::Zero());
  scratch.reserve(std::size_t(kBatchPairs) + max_count + kLanes);
  if (table.usable()) {
    if (plan.pair_class_table != table.version()) {  // once per plan and table
      plan.pair_class.resize(plan.partner.size());
      for (std::size_t r = 0; r < plan.rows.size(); ++r)
        for (int k = plan.start[r]; k < plan.start[r + 1]; ++k)
          plan.pair_class[std::size_t(k)] = table.class_pair(
              std::size_t(plan.rows[r]), std::size_t(plan.partner[std::size_t(k)]));
      plan.pair_class_table = table.version();
    }
    const contact_detail::TableStreamPairs pairs{table, contact_detail::LookedUp(scratch)};
    half_rows<kCohesive, kEnergy, kVirial>(plan, pos, image, pairs, scratch, s.force.data(),
                                           site_energy, site_virial);
  } else {
    plan.pair_class.clear();
    plan.pair_class_table = 0;
    const double eps[4] = {params.eps_cc, params.eps_cv, params.eps_cv, params.eps_vv};
    const contact_detail::DirectStreamPairs pairs{
        s.diameter.data(), table.site_kind(), eps,           params.alpha,
        params.beta,       params.alpha_cv,   params.beta_cv};
    half_rows<kCohesive, kEnergy, kVirial>(plan, pos, image, pairs, scratch, s.force.data(),
                                           site_energy, site_virial);
  }
}

#define INVASIM_HALF_ROWS(C, E, V)                                                                \
  template void contact_half_rows<C, E, V>(System&, HalfRowsPlan&, std::size_t, const PairTable&, \
                                           const ContactParams&, double*, Vec3*, RowScratch&);
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
