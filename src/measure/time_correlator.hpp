#pragma once
// Time correlation functions of a fixed group of sites (docs/measurements_dynamics.md, "Time
// correlators"), with many time origins and bounded memory: velocity autocorrelation C_vv(t) (the
// paper's per-particle normalisation and the standard one), orientation autocorrelation
// <n(0).n(t)>, mean-square displacement of the unwrapped positions, the non-Gaussian
// parameter and the self-intermediate scattering function F_s(k, t). Decorrelation times
// tau_d (C_vv = 1/e) and tau_r (F_s = 1/e) by linear interpolation between lags.
//
// The caller samples every `every` steps (sample interval every * dt). A new time origin is
// taken every `origin_every` samples; only the origins still within the lag window are kept
// (a ring of ceil(L / origin_every) snapshots of N sites), so memory does not grow with the
// run. Pure measurement: reads the System, never changes it. The sums over sites are done
// in fixed-size blocks and reduced in a fixed order, so results do not depend on the number
// of OpenMP threads.
//
// The samples between two origins are kept and correlated with the stored origins together,
// when the next origin is taken or the state is read: each origin snapshot is then read from
// memory once per origin_every samples instead of once per sample (the ring of a paper-size
// group does not fit in cache). The sums receive the same terms in the same order as when
// each sample is correlated at once, so the results are the same bits.
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "state/system.hpp"

namespace invasim {

// How F_s(k, t) = <cos(k . dr)> is averaged over the direction of k.
enum class FsAverage {
  kIsotropic,  // exact average over all directions: <sin(k |dr|) / (k |dr|)>
  kAxesYZ      // average over k along y and z (the periodic axes): <cos(k dy) + cos(k dz)> / 2
};

struct TimeCorrelatorParams {
  int lags = 100;                // L: lags 0 .. L-1, in sample intervals
  int origin_every = 1;          // a new time origin every this many samples
  double sample_interval = 1.0;  // time between two samples (every * dt)
  double k = 2.0 * M_PI;         // wave number of F_s (2 pi / sigma, sigma = 1)
  FsAverage fs_average = FsAverage::kIsotropic;
  // Channels to record (each costs a ring of snapshots): velocities (C_vv), orientations
  // (<n.n>), unwrapped positions (MSD, alpha_2, F_s).
  bool velocity = true, orientation = true, position = true;
  void validate() const;  // throws InputError naming the bad value
};

// Result columns for writing: one name per column, all columns of equal length.
struct Columns {
  std::vector<std::string> names;
  std::vector<std::vector<double>> values;
};

// The correlation functions at every lag that has at least one (origin, sample) pair.
// Columns of disabled channels are empty.
struct CorrelationFunctions {
  std::vector<double> time;          // lag time
  std::vector<double> origins;       // number of time origins averaged at this lag
  std::vector<double> cvv;           // < v(t').v(t'+t) / |v(t')|^2 > (paper)
  std::vector<double> cvv_standard;  // < v(t').v(t'+t) > / < v^2 >
  std::vector<double> vv;            // < v(t').v(t'+t) > (unnormalised)
  std::vector<double> nn;            // < n(t').n(t'+t) >
  std::vector<double> msd;           // < |r(t'+t) - r(t')|^2 >, unwrapped positions
  std::vector<double> alpha2;        // 3 <dr^4> / (5 <dr^2>^2) - 1 (NaN where msd = 0)
  std::vector<double> fs;            // F_s(k, t)
};

// Everything that changes while sampling, as plain vectors (for checkpoints). Snapshots are
// slot-major: value (slot * N + site) * 3 + axis. `sums` holds kTerms running sums per lag.
struct CorrelatorState {
  std::uint64_t samples = 0;                                    // samples taken so far
  double last_time = std::numeric_limits<double>::quiet_NaN();  // System::time of the last
  std::vector<double> velocity, orientation, position;          // origin snapshots
  std::vector<std::uint64_t> origins;                           // per lag: origins accumulated
  std::vector<double> sums;                                     // per lag x kTerms
  // Empty unless cells divided or died (TimeCorrelator::sites_changed): the group's site
  // indices once they changed, and, once cells of the group died, per lag the number of
  // (origin, sample, cell) terms summed, the normalisation in place of origins x N (a pair
  // counts the cells alive at both of its times).
  std::vector<int> group;
  std::vector<double> site_pairs;
};

class TimeCorrelator {
 public:
  // Indices of the running sums kept per lag, in CorrelatorState::sums.
  enum Term { kVV = 0, kVVNorm, kVVCount, kNN, kDR2, kDR4, kFs, kTerms };

  // group: site indices (e.g. System::sites_of_kind(SiteKind::kCancer)); must be non-empty.
  TimeCorrelator(std::vector<int> group, const TimeCorrelatorParams& params);
  // Its posted tasks point to it (see "Pending"): not copied or moved, finished when destroyed.
  TimeCorrelator(const TimeCorrelator&) = delete;
  TimeCorrelator& operator=(const TimeCorrelator&) = delete;
  ~TimeCorrelator();

  // Samples the group's velocities, orientations and unwrapped positions. Throws InputError
  // if sys.time has not advanced by sample_interval (to 1e-3 relative) since the last sample,
  // or if cells divided or died since the first sample (System::site_epoch) without
  // sites_changed being told.
  void sample(const System& sys);
  // Cells divided or died (Proliferation): new_index is the new index of every old site (-1:
  // died), epoch the System's site_epoch() after the change. The group's dead cells leave it:
  // their columns leave the stored origins, and the pairs correlated from now on average over
  // the cells alive at both of their times (daughters do not join: they have no origin). The
  // survivors keep their sums and origins. Throws InputError if no cell of the group is left.
  void sites_changed(const std::vector<int>& new_index, std::uint64_t epoch);
  // Same from arrays in group order (size N each); a disabled channel's array is ignored.
  void add_sample(const Vec3* velocity, const Vec3* orientation, const Vec3* position);

  std::uint64_t samples() const { return state_.samples; }
  const std::vector<int>& group() const { return group_; }
  const TimeCorrelatorParams& params() const { return params_; }

  CorrelationFunctions result() const;
  // Columns t, origins, then cvv, cvv_std, vv (velocity), nn (orientation), msd, alpha2, fs
  // (position), for the enabled channels.
  Columns columns() const;
  // tau_d from the paper's C_vv, from the standard one, and tau_r from F_s; nullopt when the
  // function has not fallen to 1/e within the lags reached (or the channel is off).
  std::optional<double> tau_d() const;
  std::optional<double> tau_d_standard() const;
  std::optional<double> tau_r() const;

  // The accumulated state, with the kept samples correlated first (see above); the snapshots
  // in CorrelatorState's layout (a copy: they are stored by component).
  CorrelatorState state() const;
  // Replaces the accumulated state (from a checkpoint); throws InputError if its sizes do not
  // match this correlator's group and parameters.
  void restore(CorrelatorState state);

 private:
  struct Partial;
  struct Scratch;
  // One channel's snapshots by component: value ((slot * 3 + axis) * N + site), so that the
  // per-pair loops read each component contiguously (no shuffles of 3-vectors in the lanes).
  using Components = std::vector<double>;
  void store_origin(std::size_t slot, const Vec3* v, const Vec3* n, const Vec3* r) const;
  // Correlates the kept samples with the stored origins and adds them to the sums in sample
  // order, now; logically const (the sums are what they would have been without the wait).
  void flush() const;
  // The kept samples at a new origin, as (origin, sample, block) tasks: posted to the team's
  // idle tasks (core/idle_tasks.hpp) when `idle`, else run at once; complete_pending then adds
  // their partial sums in the fixed order and stores the origin that waited for them.
  void post_kept(bool idle) const;
  void run_pending_task(std::size_t task) const;
  void complete_pending() const;
  // Terms of sites [lo, hi) for origin `slot` and the k-th pending sample.
  Partial block_terms(std::size_t slot, std::size_t k, std::size_t lo, std::size_t hi) const;
  // F_s's term of one site (displacement dr) from libm if its argument is beyond
  // fast_trig::kMaxArg, else `fast`.
  double libm_fs_term(const Vec3& dr, double fast) const;
  std::size_t slots() const;
  // Frees the kept and pending sample buffers, made again for the group's size at the next
  // sample (after the group changed size).
  void drop_sample_buffers();
  std::vector<int> group_;
  TimeCorrelatorParams params_;
  // System::site_epoch() at the first sample(const System&) since construction or restore, and
  // after each sites_changed: a sample at another epoch (cells divided or died without this
  // correlator being told) is refused.
  std::optional<std::uint64_t> site_epoch_;
  // The counters and sums; its snapshot vectors stay empty (the origins are in origin_*).
  mutable CorrelatorState state_;
  // The stored origins, `slots()` of each channel (mutable: a held-back origin is stored when
  // pending tasks complete, which a read of the state may trigger).
  mutable Components origin_v_, origin_n_, origin_r_;
  // 1 / |v|^2 of every stored origin velocity (0 for a site at rest), value (slot * N + site):
  // a product per pair instead of a division. Derived from origin_v_.
  mutable std::vector<double> inv_speed2_;
  std::vector<Vec3> v_now_, n_now_, r_now_;  // gather buffers for sample()
  // Samples taken but not yet correlated (at most origin_every), by component like the
  // origins (k in place of the slot); the first is sample state_.samples - kept_.
  mutable std::size_t kept_ = 0;
  mutable Components kept_v_, kept_n_, kept_r_;
  // Pending: kept samples handed to tasks (their buffers swapped out of kept_*), the tasks'
  // partial sums (sample, origin, block), and the origin taken when they were posted, held
  // back because its ring slot still holds an origin the tasks read.
  struct Pending {
    bool active = false, idle = false;
    std::uint64_t first = 0, o_lo = 0;
    std::size_t K = 0, n_orig = 0, blocks = 0;
    Components v, n, r;
    std::vector<Partial> partial;
    bool has_origin = false;
    std::size_t origin_slot = 0;
    std::vector<Vec3> origin_v, origin_n, origin_r;
  };
  mutable Pending pending_;
};

// First time at which y falls to `level` or below, linearly interpolated between the two
// samples around the crossing; nullopt if it never does. t and y have equal sizes.
std::optional<double> decay_time(const std::vector<double>& t, const std::vector<double>& y,
                                 double level = std::exp(-1.0));

}  // namespace invasim
