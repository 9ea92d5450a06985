#include "measure/time_correlator.hpp"

#include <algorithm>

#include "core/deterministic_sum.hpp"
#include "core/errors.hpp"
#include "core/fast_trig.hpp"
#include "core/idle_tasks.hpp"
#include "core/memory_budget.hpp"
#include "core/parallel.hpp"

namespace invasim {

void TimeCorrelatorParams::validate() const {
  if (lags < 1) fail_input("time correlator: lags = ", lags, " must be >= 1");
  if (origin_every < 1)
    fail_input("time correlator: origin_every = ", origin_every, " must be >= 1");
  if (!(sample_interval > 0.0) || !std::isfinite(sample_interval))
    fail_input("time correlator: sample_interval = ", sample_interval, " must be > 0");
  if (!(k > 0.0) || !std::isfinite(k)) fail_input("time correlator: k = ", k, " must be > 0");
  if (!velocity && !orientation && !position)
    fail_input("time correlator: velocity, orientation and position are all switched off");
}

// Running sums of one block of sites for one (origin, sample) pair.
struct TimeCorrelator::Partial {
  double t[kTerms] = {};
  Partial& operator+=(const Partial& o) {
    for (int k = 0; k < kTerms; ++k) t[k] += o.t[k];
    return *this;
  }
};

namespace {
// 1 / |v|^2, or 0 for a site at rest (which the per-particle C_vv skips).
inline double inverse_speed2(const Vec3& v) {
  const double v2 = v[0] * v[0] + (v[1] * v[1] + v[2] * v[2]);
  return v2 > 0.0 ? 1.0 / v2 : 0.0;
}
// Writes N vectors x into `to` by component: to[(base + axis) * N + i] = x[i][axis].
inline void put_components(std::vector<double>& to, std::size_t base, std::size_t N,
                           const Vec3* x) {
  double* c = to.data() + base * N;
  for (std::size_t i = 0; i < N; ++i) {
    c[i] = x[i][0];
    c[N + i] = x[i][1];
    c[2 * N + i] = x[i][2];
  }
}
// Snapshots converted between CorrelatorState's layout, interleaved ((slot * N + site) * 3 +
// axis), and the stored one, by component ((slot * 3 + axis) * N + site).
enum class To { kInterleaved, kByComponent };
std::vector<double> regrouped(const std::vector<double>& in, std::size_t N, To to) {
  std::vector<double> out(in.size());
  for (std::size_t slot = 0; slot < out.size() / (3 * N); ++slot)
    for (std::size_t i = 0; i < N; ++i)
      for (std::size_t a = 0; a < 3; ++a) {
        const std::size_t interleaved = (slot * N + i) * 3 + a, by_axis = (slot * 3 + a) * N + i;
        if (to == To::kInterleaved)
          out[interleaved] = in[by_axis];
        else
          out[by_axis] = in[interleaved];
      }
  return out;
}
// Origins j (taken at sample j E) within the window of sample s: s - L + 1 <= j E <= s.
struct OriginWindow {
  std::uint64_t L, E;
  explicit OriginWindow(const TimeCorrelatorParams& p)
      : L(std::uint64_t(p.lags)), E(std::uint64_t(p.origin_every)) {}
  std::uint64_t lo(std::uint64_t s) const { return s + 1 >= L ? (s + 1 - L + E - 1) / E : 0; }
  std::uint64_t hi(std::uint64_t s) const { return s / E; }
};
}  // namespace

TimeCorrelator::TimeCorrelator(std::vector<int> group, const TimeCorrelatorParams& params)
    : group_(std::move(group)), params_(params) {
  params_.validate();
  if (group_.empty()) fail_input("time correlator: the group of sites is empty");
  for (int i : group_)
    if (i < 0) fail_input("time correlator: site index ", i, " < 0");
  // Memory per lag, checked before allocating: the stored snapshots of the group
  // (one slot per origin_every lags) and the lag's sums.
  const int arrays = int(params_.velocity) + int(params_.orientation) + int(params_.position);
  const double per_lag = double(arrays) * double(group_.size()) * 3.0 * 8.0 /
                             double(std::max(params_.origin_every, 1)) +
                         8.0 * (1 + kTerms);
  check_memory("time correlator", "lags", double(params_.lags), per_lag);
  // And with the samples kept between two origins (origin_every of them, add_sample), the
  // whole: named by origin_every, which sizes the kept samples.
  const double per_kept = double(arrays) * double(group_.size()) * 3.0 * 8.0;
  const double every = double(params_.origin_every);
  check_memory("time correlator", "origin_every", every,
               per_kept + double(params_.lags) * per_lag / every);
  const std::size_t snap = slots() * group_.size() * 3;
  if (params_.velocity) {
    origin_v_.assign(snap, 0.0);
    inv_speed2_.assign(snap / 3, 0.0);
  }
  if (params_.orientation) origin_n_.assign(snap, 0.0);
  if (params_.position) origin_r_.assign(snap, 0.0);
  state_.origins.assign(std::size_t(params_.lags), 0);
  state_.sums.assign(std::size_t(params_.lags) * kTerms, 0.0);
}

std::size_t TimeCorrelator::slots() const {
  // (In 64 bits: lags + origin_every may exceed an int.)
  const std::int64_t lags = params_.lags, every = params_.origin_every;
  return std::size_t((lags + every - 1) / every);
}

void TimeCorrelator::sample(const System& sys) {
  const std::size_t n = group_.size();
  if (!site_epoch_) site_epoch_ = sys.site_epoch();
  if (*site_epoch_ != sys.site_epoch())
    fail_input("time correlator: cells divided or died since its first sample and it was not ",
               "told (sample it through the Simulation that runs the proliferation)");
  if (state_.samples > 0) {
    const double elapsed = sys.time - state_.last_time;
    if (std::abs(elapsed - params_.sample_interval) > 1e-3 * params_.sample_interval)
      fail_input("time correlator: sampled ", elapsed, " time units after the previous sample, ",
                 "expected sample_interval = ", params_.sample_interval);
  }
  const Sites& s = sys.sites();
  v_now_.resize(n);
  n_now_.resize(n);
  r_now_.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const int i = group_[k];
    if (std::size_t(i) >= sys.n_sites())
      fail_input("time correlator: site ", i, " is outside [0, ", sys.n_sites(), ")");
    if (params_.velocity) v_now_[k] = s.vel[i];
    if (params_.orientation) n_now_[k] = s.orient[i];
    if (params_.position) r_now_[k] = sys.unwrapped(std::size_t(i));
  }
  add_sample(v_now_.data(), n_now_.data(), r_now_.data());
  state_.last_time = sys.time;
}

void TimeCorrelator::store_origin(std::size_t slot, const Vec3* v, const Vec3* n,
                                  const Vec3* r) const {
  const std::size_t N = group_.size();
  if (params_.velocity) {
    put_components(origin_v_, 3 * slot, N, v);
    for (std::size_t i = 0; i < N; ++i) inv_speed2_[slot * N + i] = inverse_speed2(v[i]);
  }
  if (params_.orientation) put_components(origin_n_, 3 * slot, N, n);
  if (params_.position) put_components(origin_r_, 3 * slot, N, r);
}

// Per-site terms of one block, computed in vectorised loops, then summed in lanes (room for
// the last lane group's padding).
namespace {
constexpr std::size_t kLanes = 8;
}
struct TimeCorrelator::Scratch {
  static constexpr std::size_t kSize = kSumBlock + kLanes;
  double vv[kSize], vv_norm[kSize], nn[kSize], dr2[kSize], fs[kSize];
  // 1 where |v(t')| > 0 (the per-particle normalisation counts only those), else 0;
  // vv_norm is 0 where it is 0.
  double moving[kSize];
};

TimeCorrelator::Partial TimeCorrelator::block_terms(std::size_t slot, std::size_t k_sample,
                                                    std::size_t lo, std::size_t hi) const {
  Scratch sc;
  const std::size_t N = group_.size(), m = hi - lo;
  const double k = params_.k;
  // Component `axis` of sites lo.. of an origin slot or a kept sample.
  auto at = [&](const Components& c, std::size_t row, int axis) {
    return c.data() + (3 * row + std::size_t(axis)) * N + lo;
  };
  // a . b summed as Eigen's Vec3::dot does: a0 b0 + (a1 b1 + a2 b2).
  if (params_.velocity) {
    const double *ax = at(origin_v_, slot, 0), *ay = at(origin_v_, slot, 1),
                 *az = at(origin_v_, slot, 2);
    const Components& b = pending_.v;
    const double *bx = at(b, k_sample, 0), *by = at(b, k_sample, 1), *bz = at(b, k_sample, 2);
    const double* inv = inv_speed2_.data() + slot * N + lo;
#pragma omp simd
    for (std::size_t i = 0; i < m; ++i) {
      const double d = ax[i] * bx[i] + (ay[i] * by[i] + az[i] * bz[i]);
      sc.vv[i] = d;
      sc.moving[i] = inv[i] > 0.0 ? 1.0 : 0.0;
      sc.vv_norm[i] = d * inv[i];
    }
  }
  if (params_.orientation) {
    const double *ax = at(origin_n_, slot, 0), *ay = at(origin_n_, slot, 1),
                 *az = at(origin_n_, slot, 2);
    const Components& b = pending_.n;
    const double *bx = at(b, k_sample, 0), *by = at(b, k_sample, 1), *bz = at(b, k_sample, 2);
#pragma omp simd
    for (std::size_t i = 0; i < m; ++i) sc.nn[i] = ax[i] * bx[i] + (ay[i] * by[i] + az[i] * bz[i]);
  }
  if (params_.position) {
    const double* r0[3] = {at(origin_r_, slot, 0), at(origin_r_, slot, 1), at(origin_r_, slot, 2)};
    const Components& b = pending_.r;
    const double* r[3] = {at(b, k_sample, 0), at(b, k_sample, 1), at(b, k_sample, 2)};
    // dr = r(t) - r(t'), |dr|^2 summed as Eigen's squaredNorm does.
    auto dr = [&](std::size_t i, int a) { return r[a][i] - r0[a][i]; };
    double max_arg = 0.0;  // largest argument of sin / cos (libm beyond fast_trig::kMaxArg)
    if (params_.fs_average == FsAverage::kIsotropic) {
#pragma omp simd reduction(max : max_arg)
      for (std::size_t i = 0; i < m; ++i) {
        const double dx = dr(i, 0), dy = dr(i, 1), dz = dr(i, 2);
        const double r2 = dx * dx + (dy * dy + dz * dz), x = k * std::sqrt(r2);
        sc.dr2[i] = r2;
        max_arg = std::max(max_arg, x);
        sc.fs[i] = fast_trig::sinc(std::min(x, fast_trig::kMaxArg));
      }
    } else {
#pragma omp simd reduction(max : max_arg)
      for (std::size_t i = 0; i < m; ++i) {
        const double dx = dr(i, 0), dy = dr(i, 1), dz = dr(i, 2);
        const double xy = std::abs(k * dy), xz = std::abs(k * dz);
        sc.dr2[i] = dx * dx + (dy * dy + dz * dz);
        max_arg = std::max(max_arg, std::max(xy, xz));
        sc.fs[i] = 0.5 * (fast_trig::cos(std::min(xy, fast_trig::kMaxArg)) +
                          fast_trig::cos(std::min(xz, fast_trig::kMaxArg)));
      }
    }
    if (max_arg > fast_trig::kMaxArg)  // clamped above: redone with libm
      for (std::size_t i = 0; i < m; ++i)
        sc.fs[i] = libm_fs_term(Vec3(dr(i, 0), dr(i, 1), dr(i, 2)), sc.fs[i]);
  }
  // The sums in kLanes interleaved lanes (site i adds to lane i mod kLanes), which vectorise,
  // then the lanes in order: a fixed order for a block, whatever the thread count. The last
  // lane group is padded with zero terms.
  const std::size_t padded = (m + kLanes - 1) / kLanes * kLanes;
  double lane[kTerms][kLanes] = {};
  auto add_lanes = [&](int term, const double* x) {
    for (std::size_t i0 = 0; i0 < padded; i0 += kLanes)
      for (std::size_t l = 0; l < kLanes; ++l) lane[term][l] += x[i0 + l];
  };
  if (params_.velocity) {
    for (std::size_t i = m; i < padded; ++i) sc.vv[i] = sc.vv_norm[i] = sc.moving[i] = 0.0;
    add_lanes(kVV, sc.vv);
    add_lanes(kVVNorm, sc.vv_norm);
    add_lanes(kVVCount, sc.moving);
  }
  if (params_.orientation) {
    for (std::size_t i = m; i < padded; ++i) sc.nn[i] = 0.0;
    add_lanes(kNN, sc.nn);
  }
  if (params_.position) {
    for (std::size_t i = m; i < padded; ++i) sc.dr2[i] = sc.fs[i] = 0.0;
    add_lanes(kDR2, sc.dr2);
    for (std::size_t i0 = 0; i0 < padded; i0 += kLanes)
      for (std::size_t l = 0; l < kLanes; ++l) lane[kDR4][l] += sc.dr2[i0 + l] * sc.dr2[i0 + l];
    add_lanes(kFs, sc.fs);
  }
  Partial p;
  for (int t = 0; t < kTerms; ++t)
    for (std::size_t l = 0; l < kLanes; ++l) p.t[t] += lane[t][l];
  return p;
}

double TimeCorrelator::libm_fs_term(const Vec3& dr, double fast) const {
  const double k = params_.k;
  if (params_.fs_average == FsAverage::kIsotropic) {
    const double x = k * dr.norm();
    return x > fast_trig::kMaxArg ? std::sin(x) / x : fast;
  }
  const double xy = std::abs(k * dr[1]), xz = std::abs(k * dr[2]);
  return std::max(xy, xz) > fast_trig::kMaxArg ? 0.5 * (std::cos(xy) + std::cos(xz)) : fast;
}

void TimeCorrelator::add_sample(const Vec3* v, const Vec3* n, const Vec3* r) {
  const std::uint64_t s = state_.samples, E = std::uint64_t(params_.origin_every);
  const std::size_t N = group_.size();
  // The kept samples use origins up to (s - 1) / E; origin s / E replaces the oldest slot.
  if (s % E == 0) {
    // The kept samples go to the team's idle tasks; the new origin replaces the oldest slot,
    // which they still read, once they are done (complete_pending).
    complete_pending();
    post_kept(true);
    const std::size_t slot = std::size_t((s / E) % slots());
    if (pending_.active) {
      pending_.has_origin = true;
      pending_.origin_slot = slot;
      if (params_.velocity) pending_.origin_v.assign(v, v + N);
      if (params_.orientation) pending_.origin_n.assign(n, n + N);
      if (params_.position) pending_.origin_r.assign(r, r + N);
    } else {
      store_origin(slot, v, n, r);
    }
  }
  if (kept_v_.empty() && kept_n_.empty() && kept_r_.empty()) {
    // Allocated at the first sample: E samples of each channel.
    const std::size_t cap = std::size_t(E) * 3 * N;
    if (params_.velocity) kept_v_.resize(cap);
    if (params_.orientation) kept_n_.resize(cap);
    if (params_.position) kept_r_.resize(cap);
  }
  if (params_.velocity) put_components(kept_v_, 3 * kept_, N, v);
  if (params_.orientation) put_components(kept_n_, 3 * kept_, N, n);
  if (params_.position) put_components(kept_r_, 3 * kept_, N, r);
  ++kept_;
  ++state_.samples;
}

void TimeCorrelator::flush() const {
  complete_pending();
  post_kept(false);
  complete_pending();
}

void TimeCorrelator::post_kept(bool idle) const {
  if (kept_ == 0) return;
  const OriginWindow window(params_);
  Pending& p = pending_;
  p.first = state_.samples - kept_;
  p.o_lo = window.lo(p.first);
  p.K = kept_;
  p.n_orig = std::size_t(window.hi(state_.samples - 1) - p.o_lo + 1);
  p.blocks = (group_.size() + kSumBlock - 1) / kSumBlock;
  // The kept samples move to the tasks; kept_* get the buffers of the last ones.
  p.v.swap(kept_v_);
  p.n.swap(kept_n_);
  p.r.swap(kept_r_);
  kept_ = 0;
  // One partial sum per (sample, origin, block of sites); they are added in a fixed order, so
  // the sums do not depend on which thread ran which task, or when.
  p.partial.assign(p.K * p.n_orig * p.blocks, Partial{});
  p.active = true;
  p.idle = idle;
  const std::size_t tasks = p.partial.size();
  if (idle) {
    idle_tasks().post(tasks, [this](std::size_t t) { run_pending_task(t); });
    return;
  }
  // Small work is not worth waking the thread team (core/parallel.hpp).
#pragma omp parallel for schedule(static) if (parallel_light(p.K * p.n_orig * group_.size()))
  for (std::int64_t t = 0; t < std::int64_t(tasks); ++t) run_pending_task(std::size_t(t));
}

void TimeCorrelator::run_pending_task(std::size_t task) const {
  const Pending& p = pending_;
  const std::size_t b = task % p.blocks, o = (task / p.blocks) % p.n_orig,
                    k = task / (p.blocks * p.n_orig);
  const OriginWindow window(params_);
  const std::uint64_t j = p.o_lo + o, s = p.first + k;
  if (j < window.lo(s) || j > window.hi(s)) return;
  const std::size_t N = group_.size(), lo = b * kSumBlock, hi = std::min(N, lo + kSumBlock);
  pending_.partial[task] = block_terms(std::size_t(j % slots()), k, lo, hi);
}

void TimeCorrelator::complete_pending() const {
  Pending& p = pending_;
  if (!p.active) return;
  if (p.idle) idle_tasks().finish();
  const OriginWindow window(params_);
  for (std::size_t k = 0; k < p.K; ++k) {
    const std::uint64_t s = p.first + k;
    for (std::uint64_t j = window.lo(s); j <= window.hi(s); ++j) {
      const std::size_t o = std::size_t(j - p.o_lo);
      Partial total;
      for (std::size_t b = 0; b < p.blocks; ++b)
        total += p.partial[(k * p.n_orig + o) * p.blocks + b];
      const std::size_t lag = std::size_t(s - j * window.E);
      for (int t = 0; t < kTerms; ++t) state_.sums[lag * kTerms + t] += total.t[t];
      ++state_.origins[lag];
      if (!state_.site_pairs.empty()) state_.site_pairs[lag] += double(group_.size());
    }
  }
  p.active = false;
  if (p.has_origin) {
    p.has_origin = false;
    store_origin(p.origin_slot, p.origin_v.data(), p.origin_n.data(), p.origin_r.data());
  }
}

TimeCorrelator::~TimeCorrelator() {
  if (pending_.active && pending_.idle) idle_tasks().finish();
}

CorrelationFunctions TimeCorrelator::result() const {
  flush();
  CorrelationFunctions f;
  const double N = double(group_.size());
  const std::size_t reached =
      std::size_t(std::min<std::uint64_t>(state_.samples, std::uint64_t(params_.lags)));
  auto sum = [&](std::size_t lag, Term t) { return state_.sums[lag * kTerms + t]; };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // The (origin, sample, cell) terms of a lag: origins x N, unless cells of the group died.
  auto pairs_at = [&](std::size_t lag) {
    return state_.site_pairs.empty() ? double(state_.origins[lag]) * N : state_.site_pairs[lag];
  };
  for (std::size_t lag = 0; lag < reached; ++lag) {
    const double pairs = pairs_at(lag);
    f.time.push_back(double(lag) * params_.sample_interval);
    f.origins.push_back(double(state_.origins[lag]));
    if (params_.velocity) {
      const double vv = sum(lag, kVV) / pairs;
      const double vv0 = sum(0, kVV) / pairs_at(0);
      const double count = sum(lag, kVVCount);
      f.vv.push_back(vv);
      f.cvv_standard.push_back(vv0 > 0.0 ? vv / vv0 : nan);
      f.cvv.push_back(count > 0.0 ? sum(lag, kVVNorm) / count : nan);
    }
    if (params_.orientation) f.nn.push_back(sum(lag, kNN) / pairs);
    if (params_.position) {
      const double msd = sum(lag, kDR2) / pairs, dr4 = sum(lag, kDR4) / pairs;
      f.msd.push_back(msd);
      f.alpha2.push_back(msd > 0.0 ? 3.0 * dr4 / (5.0 * msd * msd) - 1.0 : nan);
      f.fs.push_back(sum(lag, kFs) / pairs);
    }
  }
  return f;
}

Columns TimeCorrelator::columns() const {
  CorrelationFunctions f = result();
  Columns c;
  auto add = [&](const char* name, std::vector<double>& v) {
    c.names.emplace_back(name);
    c.values.push_back(std::move(v));
  };
  add("t", f.time);
  add("origins", f.origins);
  if (params_.velocity) {
    add("cvv", f.cvv);
    add("cvv_std", f.cvv_standard);
    add("vv", f.vv);
  }
  if (params_.orientation) add("nn", f.nn);
  if (params_.position) {
    add("msd", f.msd);
    add("alpha2", f.alpha2);
    add("fs", f.fs);
  }
  return c;
}

std::optional<double> TimeCorrelator::tau_d() const {
  if (!params_.velocity) return std::nullopt;
  const CorrelationFunctions f = result();
  return decay_time(f.time, f.cvv);
}

std::optional<double> TimeCorrelator::tau_d_standard() const {
  if (!params_.velocity) return std::nullopt;
  const CorrelationFunctions f = result();
  return decay_time(f.time, f.cvv_standard);
}

std::optional<double> TimeCorrelator::tau_r() const {
  if (!params_.position) return std::nullopt;
  const CorrelationFunctions f = result();
  return decay_time(f.time, f.fs);
}

void TimeCorrelator::drop_sample_buffers() {
  for (Components* c : {&kept_v_, &kept_n_, &kept_r_, &pending_.v, &pending_.n, &pending_.r})
    c->clear();
}

void TimeCorrelator::sites_changed(const std::vector<int>& new_index, std::uint64_t epoch) {
  flush();  // every kept sample correlated with the group as it was
  const std::size_t N = group_.size();
  std::vector<std::size_t> keep;
  std::vector<int> group;
  for (std::size_t k = 0; k < N; ++k) {
    const int j = new_index.at(std::size_t(group_[k]));
    if (j < 0) continue;
    keep.push_back(k);
    group.push_back(j);
  }
  site_epoch_ = epoch;
  const std::size_t M = keep.size();
  if (M == 0) fail_input("time correlator: every cell of its group died");
  if (M < N) {
    if (state_.site_pairs.empty())
      for (std::uint64_t o : state_.origins) state_.site_pairs.push_back(double(o) * double(N));
    // Rows of N values (a slot's component, or a slot) become rows of the M survivors.
    auto compact = [&](std::vector<double>& c) {
      if (c.empty()) return;
      const std::size_t rows = c.size() / N;
      std::vector<double> out(rows * M);
      for (std::size_t r = 0; r < rows; ++r)
        for (std::size_t m = 0; m < M; ++m) out[r * M + m] = c[r * N + keep[m]];
      c.swap(out);
    };
    compact(origin_v_);
    compact(origin_n_);
    compact(origin_r_);
    compact(inv_speed2_);
    drop_sample_buffers();
  }
  if (group != group_) state_.group = group;  // checkpoints hold it from now on
  group_ = std::move(group);
}

void TimeCorrelator::restore(CorrelatorState state) {
  // A checkpoint written after cells divided or died holds the group as it is now.
  const std::size_t N = state.group.empty() ? group_.size() : state.group.size();
  const std::size_t snap = slots() * N * 3;
  auto check = [](const char* what, std::size_t got, std::size_t want) {
    if (got != want)
      fail_input("time correlator: restored ", what, " has ", got, " values, expected ", want);
  };
  check("velocity snapshots", state.velocity.size(), params_.velocity ? snap : 0);
  check("orientation snapshots", state.orientation.size(), params_.orientation ? snap : 0);
  check("position snapshots", state.position.size(), params_.position ? snap : 0);
  check("origin counts", state.origins.size(), std::size_t(params_.lags));
  check("sums", state.sums.size(), std::size_t(params_.lags) * kTerms);
  if (!state.site_pairs.empty())
    check("site pairs", state.site_pairs.size(), std::size_t(params_.lags));
  // Posted tasks read the stored origins and the group: finished before those are replaced
  // (their results are dropped).
  if (pending_.active && pending_.idle) idle_tasks().finish();
  pending_.active = pending_.has_origin = false;
  if (!state.group.empty()) {
    group_ = state.group;
    if (params_.velocity) inv_speed2_.assign(slots() * N, 0.0);
    drop_sample_buffers();
  }
  origin_v_ = regrouped(state.velocity, N, To::kByComponent);
  origin_n_ = regrouped(state.orientation, N, To::kByComponent);
  origin_r_ = regrouped(state.position, N, To::kByComponent);
  state_ = std::move(state);
  state_.velocity.clear();
  state_.orientation.clear();
  state_.position.clear();
  kept_ = 0;
  site_epoch_.reset();  // the restored System's epoch is taken at the next sample
  for (std::size_t slot = 0; slot < (params_.velocity ? slots() : 0); ++slot)
    for (std::size_t i = 0; i < N; ++i) {
      const double* c = origin_v_.data() + 3 * slot * N + i;
      inv_speed2_[slot * N + i] = inverse_speed2(Vec3(c[0], c[N], c[2 * N]));
    }
}

CorrelatorState TimeCorrelator::state() const {
  flush();
  CorrelatorState s = state_;
  const std::size_t N = group_.size();
  s.velocity = regrouped(origin_v_, N, To::kInterleaved);
  s.orientation = regrouped(origin_n_, N, To::kInterleaved);
  s.position = regrouped(origin_r_, N, To::kInterleaved);
  return s;
}

std::optional<double> decay_time(const std::vector<double>& t, const std::vector<double>& y,
                                 double level) {
  if (t.size() != y.size())
    fail_input("decay_time: ", t.size(), " times but ", y.size(), " values");
  for (std::size_t i = 0; i < y.size(); ++i) {
    if (!(y[i] <= level)) continue;
    if (i == 0) return t[0];
    // y[i-1] > level >= y[i] (y[i-1] may be NaN only if it never was <= level: skip it).
    if (!std::isfinite(y[i - 1])) return t[i];
    return t[i - 1] + (t[i] - t[i - 1]) * (y[i - 1] - level) / (y[i - 1] - y[i]);
  }
  return std::nullopt;
}

}  // namespace invasim
