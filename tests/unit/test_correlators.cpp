// Multiple-time-origin correlators (src/measure/time_correlator.hpp):
// 1. bookkeeping, exactly: every function against a brute-force evaluation over the whole
//    stored trajectory with the same time origins (ring buffer wrap-around, several blocks of
//    sites), C_vv(0) = F_s(k, 0) = 1 exactly, decay-time interpolation, checkpoint state,
//    thread-count independence;
// 2. physics, against closed forms, on trajectories of the engine (System + Dynamics, as in
//    test_dynamics.cpp): free active particles without thermal noise (C_vv, <n.n>, tau_d) and
//    free Langevin particles (MSD, F_s = exp(-k^2 MSD / 6), tau_r, alpha_2 = 0).
// Statistical tests use fixed seeds; error bars come from the scatter between independent
// groups of particles (one correlator per group), and tolerances are several errors wide.
#include <omp.h>
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <limits>
#include <thread>
#include <vector>

#include "core/errors.hpp"
#include "core/idle_tasks.hpp"
#include "core/rng.hpp"
#include "core/team_barrier.hpp"
#include "integrate/dynamics.hpp"
#include "measure/time_correlator.hpp"
#include "test_support.hpp"

using namespace invasim;

namespace {

constexpr double kDt = 0.05;
constexpr double kGamma = 0.2;
const double kInvE = std::exp(-1.0);

// ---------------------------------------------------------------------------------------
// Synthetic trajectories and a brute-force reference

struct Trajectory {
  std::vector<std::vector<Vec3>> v, n, r;  // [sample][particle]
};

// Random velocities (some exactly zero), unit orientations and random-walk positions.
Trajectory random_trajectory(int samples, int particles, std::uint64_t seed) {
  Trajectory t;
  std::vector<Vec3> r(particles, Vec3::Zero());
  for (int s = 0; s < samples; ++s) {
    std::vector<Vec3> v(particles), n(particles);
    for (int q = 0; q < particles; ++q) {
      const RandomKey key(seed, std::uint64_t(s), std::uint32_t(q), RngStream::kUser);
      v[q] = (q % 97 == 5 && s % 3 == 0) ? Vec3::Zero() : key.normal3();
      n[q] = RandomKey(seed, std::uint64_t(s), std::uint32_t(q), RngStream::kUser, 1)
                 .normal3()
                 .normalized();
      r[q] +=
          0.3 * RandomKey(seed, std::uint64_t(s), std::uint32_t(q), RngStream::kUser, 2).normal3();
    }
    t.v.push_back(v);
    t.n.push_back(n);
    t.r.push_back(r);
  }
  return t;
}

// Every estimator summed directly over all (origin j E, sample j E + lag) pairs.
CorrelationFunctions brute_force(const Trajectory& t, const TimeCorrelatorParams& p) {
  CorrelationFunctions f;
  const int S = int(t.v.size()), N = int(t.v[0].size());
  const int reached = std::min(S, p.lags);
  std::vector<double> vv0;
  for (int lag = 0; lag < reached; ++lag) {
    double origins = 0, vv = 0, vvn = 0, count = 0, nn = 0, dr2 = 0, dr4 = 0, fs = 0;
    for (int o = 0; o + lag < S; o += p.origin_every) {
      origins += 1;
      for (int q = 0; q < N; ++q) {
        const Vec3 &v0 = t.v[o][q], &v1 = t.v[o + lag][q];
        vv += v0.dot(v1);
        if (v0.squaredNorm() > 0) {
          vvn += v0.dot(v1) / v0.squaredNorm();
          count += 1;
        }
        nn += t.n[o][q].dot(t.n[o + lag][q]);
        const Vec3 dr = t.r[o + lag][q] - t.r[o][q];
        dr2 += dr.squaredNorm();
        dr4 += dr.squaredNorm() * dr.squaredNorm();
        const double kr = p.k * dr.norm();
        fs += p.fs_average == FsAverage::kIsotropic
                  ? (kr == 0 ? 1.0 : std::sin(kr) / kr)
                  : 0.5 * (std::cos(p.k * dr[1]) + std::cos(p.k * dr[2]));
      }
    }
    const double pairs = origins * N;
    f.time.push_back(lag * p.sample_interval);
    f.origins.push_back(origins);
    f.vv.push_back(vv / pairs);
    f.cvv.push_back(vvn / count);
    f.cvv_standard.push_back(vv / pairs / (f.vv[0]));
    f.nn.push_back(nn / pairs);
    f.msd.push_back(dr2 / pairs);
    f.alpha2.push_back(lag == 0 ? std::nan("")
                                : 3 * dr4 / pairs / (5 * std::pow(dr2 / pairs, 2)) - 1);
    f.fs.push_back(fs / pairs);
  }
  return f;
}

void feed(TimeCorrelator& c, const Trajectory& t, int from, int to) {
  for (int s = from; s < to; ++s) c.add_sample(t.v[s].data(), t.n[s].data(), t.r[s].data());
}

void require_close(const std::vector<double>& a, const std::vector<double>& b, const char* what) {
  REQUIRE(a.size() == b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    INFO(what << " at lag " << i << ": " << a[i] << " vs brute force " << b[i]);
    if (std::isnan(b[i])) {
      CHECK(std::isnan(a[i]));
    } else {
      CHECK(std::abs(a[i] - b[i]) <= 1e-12 * std::max(1.0, std::abs(b[i])));
    }
  }
}

// ---------------------------------------------------------------------------------------
// Closed forms

// Continuous-time <v(0).v(t)>/<v^2> of m dv/dt = -gamma v + f0 n (Caprini & Marconi 2021).
double active_vacf(double t, double tau_g, double tau_p) {
  return (tau_g * std::exp(-t / tau_g) - tau_p * std::exp(-t / tau_p)) / (tau_g - tau_p);
}

// MSD of a free Langevin particle (m = 1) in equilibrium: 6 (kT/gamma) [t - tau_g (1 -
// e^-t/tau_g)].
double langevin_msd(double t, double kT, double gamma) {
  const double tau_g = 1.0 / gamma;
  return 6.0 * kT / gamma * (t - tau_g * (1.0 - std::exp(-t / tau_g)));
}

// The same for the engine's scheme (used to report its discretisation error): positions
// advance by dt u with the half-step velocity u, an AR(1) process u' = b u + dt xi / m with
// b = 1 - gamma dt / m and stationary variance (kT/m) / (1 - gamma dt / 2m) per component.
double langevin_msd_discrete(int steps, double kT, double gamma, double dt) {
  const double a = gamma * dt / 2.0, b = 1.0 - 2.0 * a, var_u = kT / (1.0 - a);
  double s = steps;
  for (int k = 1; k < steps; ++k) s += 2.0 * (steps - k) * std::pow(b, k);
  return 3.0 * dt * dt * var_u * s;
}

// Root of a decreasing f(t) - level on [0, hi] by bisection.
template <typename F>
double root(F f, double level, double hi) {
  double lo = 0.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) > level ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// ---------------------------------------------------------------------------------------
// Engine trajectories

using test::all_sites;
using test::estimate;
using test::Estimate;

// n non-interacting unit-mass spheres at random positions in a fully periodic box.
System free_particles(int n, std::uint64_t seed) {
  return test::free_particles(n, 1.0, seed);
}

// Independent correlators over equal groups of particles. Every group has as many particles
// and time origins, so the element-wise mean of their functions is the average over all
// particles (for the ratio cvv_std, the mean of the groups' ratios), and their scatter gives
// the standard error.
struct GroupCorrelators {
  std::deque<TimeCorrelator> groups;  // (not copied or moved)
  GroupCorrelators(const std::vector<int>& sites, int n_groups, const TimeCorrelatorParams& p) {
    const int n = int(sites.size()), size = n / n_groups;
    REQUIRE(size * n_groups == n);
    for (int g = 0; g < n_groups; ++g)
      groups.emplace_back(
          std::vector<int>(sites.begin() + g * size, sites.begin() + (g + 1) * size), p);
  }
  void sample(const System& sys) {
    for (auto& g : groups) g.sample(sys);
  }
  CorrelationFunctions mean() const {
    CorrelationFunctions m = groups[0].result();
    for (auto* v : {&m.cvv, &m.cvv_standard, &m.vv, &m.nn, &m.msd, &m.alpha2, &m.fs})
      std::fill(v->begin(), v->end(), 0.0);
    const double w = 1.0 / double(groups.size());
    for (const auto& g : groups) {
      const CorrelationFunctions f = g.result();
      for (auto pick :
           {&CorrelationFunctions::cvv, &CorrelationFunctions::cvv_standard,
            &CorrelationFunctions::vv, &CorrelationFunctions::nn, &CorrelationFunctions::msd,
            &CorrelationFunctions::alpha2, &CorrelationFunctions::fs})
        for (std::size_t i = 0; i < (f.*pick).size(); ++i) (m.*pick)[i] += w * (f.*pick)[i];
    }
    return m;
  }
  // Standard error of one function (a member of CorrelationFunctions) at lag index i.
  double error(std::vector<double> CorrelationFunctions::*pick, std::size_t i) const {
    std::vector<double> x;
    for (const auto& g : groups) x.push_back((g.result().*pick)[i]);
    return estimate(x).error;
  }
};

}  // namespace

// =======================================================================================
// 1. Bookkeeping

TEST_CASE("correlator equals a brute-force sum over all stored origins", "[correlator]") {
  struct Case {
    int lags, origin_every, samples, particles;
    FsAverage fs;
  };
  // Ring wrap-around with lags a multiple of origin_every and not, a single lag, origins
  // rarer than the window, fewer samples than lags, 1100 particles (three site blocks), and
  // enough (origin, site) pairs per sample for the parallel path.
  for (const Case c :
       {Case{7, 3, 40, 5, FsAverage::kIsotropic}, Case{6, 3, 31, 5, FsAverage::kAxesYZ},
        Case{1, 1, 10, 3, FsAverage::kIsotropic}, Case{10, 1, 25, 4, FsAverage::kIsotropic},
        Case{4, 10, 45, 4, FsAverage::kAxesYZ}, Case{30, 2, 12, 4, FsAverage::kIsotropic},
        Case{9, 4, 30, 1100, FsAverage::kIsotropic}, Case{40, 2, 50, 1100, FsAverage::kAxesYZ}}) {
    INFO("lags " << c.lags << ", origin_every " << c.origin_every << ", samples " << c.samples
                 << ", particles " << c.particles);
    TimeCorrelatorParams p;
    p.lags = c.lags;
    p.origin_every = c.origin_every;
    p.sample_interval = 0.25;
    p.k = 3.0;
    p.fs_average = c.fs;
    const Trajectory t = random_trajectory(c.samples, c.particles, 99 + c.lags);
    std::vector<int> group(c.particles);
    for (int q = 0; q < c.particles; ++q) group[q] = q;
    TimeCorrelator corr(group, p);
    feed(corr, t, 0, c.samples);
    const CorrelationFunctions f = corr.result(), ref = brute_force(t, p);
    CHECK(corr.samples() == std::uint64_t(c.samples));
    REQUIRE(f.time.size() == std::size_t(std::min(c.samples, c.lags)));
    // Origins at lag l: samples 0, E, 2E, ... with a partner l later.
    for (std::size_t lag = 0; lag < f.origins.size(); ++lag)
      CHECK(f.origins[lag] == double((c.samples - 1 - int(lag)) / c.origin_every + 1));
    require_close(f.time, ref.time, "t");
    require_close(f.origins, ref.origins, "origins");
    require_close(f.vv, ref.vv, "vv");
    require_close(f.cvv, ref.cvv, "cvv");
    require_close(f.cvv_standard, ref.cvv_standard, "cvv_standard");
    require_close(f.nn, ref.nn, "nn");
    require_close(f.msd, ref.msd, "msd");
    require_close(f.alpha2, ref.alpha2, "alpha2");
    require_close(f.fs, ref.fs, "fs");
    // Exactly 1 at t = 0 (not just to round-off).
    CHECK(f.cvv[0] == 1.0);
    CHECK(f.cvv_standard[0] == 1.0);
    CHECK(f.fs[0] == 1.0);
    CHECK(f.msd[0] == 0.0);
  }
}

TEST_CASE("F_s: displacements beyond the fast sine's range fall back to libm", "[correlator]") {
  // k |dr| from 0 to 1.7e6, across fast_trig::kMaxArg = 1e6: the fast sin / cos clamp their
  // argument there and the correlator redoes those terms with std::sin / std::cos.
  const int S = 8, N = 5;
  for (const FsAverage fs : {FsAverage::kIsotropic, FsAverage::kAxesYZ}) {
    Trajectory t = random_trajectory(S, N, 17);
    for (int s = 0; s < S; ++s)
      for (int q = 0; q < N; ++q) t.r[s][q] += Vec3(0.5, 1.0, 0.7).normalized() * 2e4 * s * q;
    TimeCorrelatorParams p;
    p.lags = S;
    p.k = 3.0;
    p.fs_average = fs;
    std::vector<int> group(N);
    for (int q = 0; q < N; ++q) group[q] = q;
    TimeCorrelator corr(group, p);
    feed(corr, t, 0, S);
    require_close(corr.result().fs, brute_force(t, p).fs, "fs");
  }
}

TEST_CASE("rotating velocities: C_vv = cos(w t) in both normalisations, MSD exact",
          "[correlator]") {
  // v_q(t) = A_q (cos(w t + p_q), sin(w t + p_q), 0), r_q(t) = (A_q / w)(sin, -cos, 0):
  // v(t').v(t'+t) / |v(t')|^2 = cos(w t), |dr|^2 = 2 A_q^2 (1 - cos w t) / w^2.
  const int N = 50, S = 300;
  const double w = 0.37, dt = 0.5;
  TimeCorrelatorParams p;
  p.lags = 40;
  p.origin_every = 7;
  p.sample_interval = dt;
  TimeCorrelator corr(all_sites(free_particles(N, 1)), p);
  double mean_a2 = 0.0;
  for (int q = 0; q < N; ++q) mean_a2 += std::pow(0.5 + 0.03 * q, 2) / N;
  std::vector<Vec3> v(N), n(N), r(N);
  for (int s = 0; s < S; ++s) {
    for (int q = 0; q < N; ++q) {
      const double a = 0.5 + 0.03 * q, ph = w * s * dt + 0.1 * q;
      v[q] = a * Vec3(std::cos(ph), std::sin(ph), 0.0);
      n[q] = Vec3(std::cos(ph), std::sin(ph), 0.0);
      r[q] = a / w * Vec3(std::sin(ph), -std::cos(ph), 0.0);
    }
    corr.add_sample(v.data(), n.data(), r.data());
  }
  const CorrelationFunctions f = corr.result();
  for (std::size_t i = 0; i < f.time.size(); ++i) {
    const double c = std::cos(w * f.time[i]);
    CHECK(f.cvv[i] == Approx(c).margin(1e-12));
    CHECK(f.cvv_standard[i] == Approx(c).margin(1e-12));
    CHECK(f.nn[i] == Approx(c).margin(1e-12));
    CHECK(f.msd[i] == Approx(2 * mean_a2 * (1 - c) / (w * w)).margin(1e-12));
  }
  // tau_d: the linear interpolation of cos(w t) between the samples around the crossing
  // (within 2e-3 of the root acos(1/e) / w, as w dt = 0.185 rad).
  const double root = std::acos(kInvE) / w;
  const double t0 = std::floor(root / dt) * dt, t1 = t0 + dt;
  const double c0 = std::cos(w * t0), c1 = std::cos(w * t1);
  const double interpolated = t0 + dt * (c0 - kInvE) / (c0 - c1);
  REQUIRE(corr.tau_d().has_value());
  CHECK(*corr.tau_d() == Approx(interpolated).epsilon(1e-10));
  CHECK(*corr.tau_d_standard() == Approx(interpolated).epsilon(1e-10));
  CHECK(interpolated == Approx(root).epsilon(2e-3));
}

TEST_CASE("decay_time interpolates linearly and reports 'not reached'", "[correlator]") {
  std::vector<double> t, y;
  for (int i = 0; i <= 10; ++i) {
    t.push_back(0.5 * i);
    y.push_back(1.0 - 0.1 * i);  // linear: crosses 1/e at (1 - 1/e) * 5 exactly
  }
  REQUIRE(decay_time(t, y).has_value());
  CHECK(*decay_time(t, y) == Approx(5.0 * (1.0 - kInvE)).epsilon(1e-14));
  CHECK(*decay_time(t, y, 0.3) == Approx(3.5).epsilon(1e-14));  // on a sample
  CHECK_FALSE(decay_time(t, y, -0.5).has_value());              // never reached
  CHECK(*decay_time(t, y, 2.0) == 0.0);                         // at once
  CHECK_FALSE(decay_time({}, {}).has_value());
  CHECK_THROWS_AS(decay_time(t, {1.0}), InputError);
  // exp(-t/tau) sampled every tau/10: interpolation error below 1e-3 relative.
  std::vector<double> te, ye;
  for (int i = 0; i < 30; ++i) {
    te.push_back(0.2 * i);
    ye.push_back(std::exp(-0.2 * i / 2.0));
  }
  CHECK(*decay_time(te, ye) == Approx(2.0).epsilon(1e-3));
  // A correlator whose F_s and C_vv never fall to 1/e reports nullopt.
  TimeCorrelatorParams p;
  p.lags = 5;
  TimeCorrelator still({0, 1}, p);
  const std::vector<Vec3> v = {Vec3(1, 0, 0), Vec3(0, 1, 0)}, r = {Vec3::Zero(), Vec3::Ones()};
  for (int s = 0; s < 8; ++s) still.add_sample(v.data(), v.data(), r.data());
  CHECK_FALSE(still.tau_d().has_value());
  CHECK_FALSE(still.tau_r().has_value());
  TimeCorrelatorParams no_pos = p;
  no_pos.position = false;
  CHECK_FALSE(TimeCorrelator({0}, no_pos).tau_r().has_value());
}

TEST_CASE("correlator state: restore continues exactly, results independent of threads",
          "[correlator]") {
  const int N = 1300, S = 60;
  const Trajectory t = random_trajectory(S, N, 7);
  TimeCorrelatorParams p;
  p.lags = 40;  // up to 20 origins x 1300 sites: above the parallel threshold
  p.origin_every = 2;
  std::vector<int> group(N);
  for (int q = 0; q < N; ++q) group[q] = q;

  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  TimeCorrelator one(group, p);
  feed(one, t, 0, S);
  omp_set_num_threads(2);
  TimeCorrelator two(group, p);
  feed(two, t, 0, S);
  omp_set_num_threads(saved);
  CHECK(one.state().sums == two.state().sums);  // bitwise
  CHECK(one.state().origins == two.state().origins);

  // Stop at sample 23 (mid-window), copy the state into a fresh correlator, continue.
  TimeCorrelator first(group, p);
  feed(first, t, 0, 23);
  TimeCorrelator resumed(group, p);
  resumed.restore(first.state());
  feed(resumed, t, 23, S);
  CHECK(resumed.state().sums == one.state().sums);
  CHECK(resumed.state().velocity == one.state().velocity);
  CHECK(resumed.samples() == std::uint64_t(S));

  // The same samples with a 2-thread team between them, whose barrier waits take the posted
  // (origin, sample, block) tasks (core/idle_tasks.hpp): the same bits.
  TimeCorrelator busy(group, p);
  for (int k = 0; k < S; ++k) {
    feed(busy, t, k, k + 1);
#pragma omp parallel num_threads(2)
    for (int q = 0; q < 6; ++q) {
      if (omp_get_thread_num() == 0) std::this_thread::sleep_for(std::chrono::microseconds(50));
      team_barrier();
    }
  }
  CHECK(busy.state().sums == one.state().sums);
  CHECK(busy.state().origins == one.state().origins);
  CHECK(busy.state().position == one.state().position);
  // Destroyed or restored with tasks still posted: they are finished first.
  {
    TimeCorrelator dropped(group, p);
    feed(dropped, t, 0, 2 * p.origin_every + 1);
    CHECK(idle_tasks().posted());
  }
  CHECK_FALSE(idle_tasks().posted());
  TimeCorrelator replaced(group, p);
  feed(replaced, t, 0, 2 * p.origin_every + 1);
  replaced.restore(first.state());
  feed(replaced, t, 23, S);
  CHECK(replaced.state().sums == one.state().sums);

  // A state of another shape is refused.
  TimeCorrelatorParams other = p;
  other.lags = 41;
  TimeCorrelator wrong(group, other);
  CHECK_THROWS_AS(wrong.restore(one.state()), InputError);
  other = p;
  other.orientation = false;
  TimeCorrelator no_orient(group, other);
  CHECK_THROWS_AS(no_orient.restore(one.state()), InputError);

  // The columns: names and equal lengths; a disabled channel is left out.
  const Columns cols = one.columns();
  CHECK(cols.names == std::vector<std::string>{"t", "origins", "cvv", "cvv_std", "vv", "nn", "msd",
                                               "alpha2", "fs"});
  for (const auto& c : cols.values) CHECK(c.size() == 40);
  no_orient.restore([&] {
    TimeCorrelator tmp(group, other);
    feed(tmp, t, 0, 5);
    return tmp.state();
  }());
  CHECK(no_orient.columns().names ==
        std::vector<std::string>{"t", "origins", "cvv", "cvv_std", "vv", "msd", "alpha2", "fs"});
}

TEST_CASE("correlator: samples kept until the next origin give the same bits as at once",
          "[correlator]") {
  // Reading the state correlates the kept samples at once, as without the wait; the deferred
  // correlator must match it bit for bit: the same origins per sample from a ring that the
  // next origin has not yet overwritten (wrap-around, lags not a multiple of origin_every,
  // three site blocks). Within one wait each lag receives at most one (origin, sample) term.
  const int N = 1100, S = 57;
  const Trajectory t = random_trajectory(S, N, 11);
  TimeCorrelatorParams p;
  p.lags = 23;
  p.origin_every = 5;
  std::vector<int> group(N);
  for (int q = 0; q < N; ++q) group[q] = q;
  TimeCorrelator at_once(group, p), deferred(group, p);
  for (int s = 0; s < S; ++s) {
    feed(at_once, t, s, s + 1);
    (void)at_once.state();  // correlates the sample now
  }
  feed(deferred, t, 0, S);
  CHECK(deferred.state().sums == at_once.state().sums);  // bitwise
  CHECK(deferred.state().origins == at_once.state().origins);
  CHECK(deferred.state().position == at_once.state().position);
}

TEST_CASE("correlator input checks", "[correlator]") {
  TimeCorrelatorParams p;
  CHECK_THROWS_AS(TimeCorrelator({}, p), InputError);
  CHECK_THROWS_AS(TimeCorrelator({-1}, p), InputError);
  for (auto bad : {&TimeCorrelatorParams::lags, &TimeCorrelatorParams::origin_every}) {
    TimeCorrelatorParams q;
    q.*bad = 0;
    CHECK_THROWS_AS(TimeCorrelator({0}, q), InputError);
  }
  TimeCorrelatorParams q;
  q.sample_interval = 0.0;
  CHECK_THROWS_AS(TimeCorrelator({0}, q), InputError);
  q = p;
  q.k = -1.0;
  CHECK_THROWS_AS(TimeCorrelator({0}, q), InputError);
  q = p;
  q.velocity = q.orientation = q.position = false;
  CHECK_THROWS_AS(TimeCorrelator({0}, q), InputError);
  // origin_every sizes the samples kept between origins (3 N doubles each): the largest int
  // needs terabytes and is refused by name (lags + origin_every also exceeds an int).
  q = p;
  q.origin_every = std::numeric_limits<int>::max();
  CHECK_THROWS_WITH(TimeCorrelator({0, 1, 2, 3, 4}, q),
                    Catch::Matchers::Contains("origin_every = 2147483647 needs about"));

  // sample(System) checks the spacing of the samples in time and the site indices.
  System sys = free_particles(4, 3);
  ForceField ff;
  Dynamics dyn(kDt);
  dyn.add(Method::langevin(all_sites(sys), kGamma, 1e-3));
  p.sample_interval = 2 * kDt;
  TimeCorrelator c(all_sites(sys), p);
  c.sample(sys);
  dyn.run(sys, ff, 2);
  c.sample(sys);
  dyn.run(sys, ff, 3);
  CHECK_THROWS_AS(c.sample(sys), InputError);
  CHECK(c.samples() == 2);
  TimeCorrelator outside({0, 4}, p);
  CHECK_THROWS_AS(outside.sample(sys), InputError);

  // A correlator that has sampled one System, then restored from the state of another whose
  // cells had divided (another site epoch, as load_checkpoint restores it): its next sample of
  // that System is accepted (the epoch is taken anew after a restore).
  System later = free_particles(4, 5);
  later.set_site_epoch(7);
  Dynamics later_dyn(kDt);
  later_dyn.add(Method::langevin(all_sites(later), kGamma, 1e-3));
  TimeCorrelator source(all_sites(later), p);
  source.sample(later);
  TimeCorrelator restored(all_sites(sys), p);
  restored.sample(sys);
  restored.restore(source.state());
  later_dyn.run(later, ff, 2);
  CHECK_NOTHROW(restored.sample(later));
  CHECK(restored.samples() == 2);
}

// =======================================================================================
// 2. Free active particles (no thermal noise): C_vv and <n.n> against the closed forms

namespace {

// n free active particles with random (stationary) orientations, equilibrated for `equil`
// steps, then sampled every `every` steps for `samples` samples.
GroupCorrelators run_active(int n, double tau_p, double f0, int equil, int every, int samples,
                            const TimeCorrelatorParams& p, std::uint64_t seed) {
  System sys = free_particles(n, seed);
  ForceField ff;
  Dynamics dyn(kDt);
  const auto group = all_sites(sys);
  auto method = Method::active(group, kGamma, f0, tau_p);
  method->randomize_orientations(sys);
  dyn.add(method);
  dyn.run(sys, ff, std::uint64_t(equil));
  GroupCorrelators c(group, 10, p);
  for (int s = 0; s < samples; ++s) {
    if (s > 0) dyn.run(sys, ff, std::uint64_t(every));
    c.sample(sys);
  }
  return c;
}

// Checks C_vv (column `pick`) against the closed form within `rel` wherever it is above 0.1,
// and <n.n> against exp(-t/tau_p) within 3% for t <= 2 tau_p; prints the deviations.
void check_active(const GroupCorrelators& c, double tau_p, double rel, const char* name,
                  std::vector<double> CorrelationFunctions::*pick) {
  const double tau_g = 1.0 / kGamma;
  const CorrelationFunctions f = c.mean();
  const std::vector<double>& cvv = f.*pick;
  double worst = 0.0, worst_sigma = 0.0, worst_n = 0.0;
  int checked = 0;
  for (std::size_t i = 0; i < f.time.size(); ++i) {
    const double t = f.time[i], exact = active_vacf(t, tau_g, tau_p);
    if (exact > 0.1) {
      const double sigma = c.error(pick, i);
      INFO(name << ", tau_p = " << tau_p << ", t = " << t << ": " << cvv[i] << " +- " << sigma
                << ", exact " << exact);
      CHECK(std::abs(cvv[i] - exact) < rel * exact);
      worst = std::max(worst, std::abs(cvv[i] / exact - 1.0));
      worst_sigma = std::max(worst_sigma, sigma / exact);
      ++checked;
    }
    if (t <= 2.0 * tau_p) {
      const double en = std::exp(-t / tau_p);
      INFO("tau_p = " << tau_p << ", t = " << t << ": <n.n> = " << f.nn[i] << ", exact " << en);
      CHECK(std::abs(f.nn[i] - en) < 0.03 * en);
      worst_n = std::max(worst_n, std::abs(f.nn[i] / en - 1.0));
    }
  }
  std::printf(
      "[correlators] active tau_p = %g, %s: %d lags with C > 0.1, max rel. deviation %.4f "
      "(largest rel. standard error %.4f); <n.n> max rel. deviation %.4f\n",
      tau_p, name, checked, worst, worst_sigma, worst_n);
  CHECK(checked >= 10);
}

}  // namespace

TEST_CASE(
    "free active particles, tau_p = 2 (~ tau_g): C_vv (both normalisations) and <n.n> "
    "exact, tau_d",
    "[correlator][active]") {
  // 4000 particles in 10 groups, 10 tau_g of equilibration, 400 time units sampled every
  // 0.25; lags to t = 15, a new origin every time unit.
  TimeCorrelatorParams p;
  p.lags = 61;
  p.origin_every = 4;
  p.sample_interval = 5 * kDt;
  p.position = false;
  const double tau_p = 2.0, tau_g = 1.0 / kGamma;
  const GroupCorrelators c = run_active(4000, tau_p, 0.02, 1000, 5, 1600, p, 0xC0A2ull);
  check_active(c, tau_p, 0.03, "standard normalisation", &CorrelationFunctions::cvv_standard);
  // The paper's per-particle normalisation agrees too: E[v(t) | v(0)] is nearly linear in
  // v(0) for free active particles (exactly so in the Gaussian limits tau_p << tau_g and
  // n frozen), so dividing by |v(0)|^2 before or after averaging hardly matters.
  check_active(c, tau_p, 0.03, "paper's normalisation", &CorrelationFunctions::cvv);
  for (const auto& g : c.groups) {
    const CorrelationFunctions f = g.result();
    CHECK(f.cvv[0] == 1.0);
    CHECK(f.cvv_standard[0] == 1.0);
    CHECK(f.nn[0] == Approx(1.0).epsilon(1e-14));  // unit vectors
  }
  // tau_d of the standard normalisation against the root of the closed form.
  const CorrelationFunctions f = c.mean();
  const double exact = root([&](double t) { return active_vacf(t, tau_g, tau_p); }, kInvE, 100.0);
  const auto tau_std = decay_time(f.time, f.cvv_standard), tau_paper = decay_time(f.time, f.cvv);
  REQUIRE(tau_std.has_value());
  REQUIRE(tau_paper.has_value());
  std::printf(
      "[correlators] active tau_p = 2: tau_d (standard) = %.4f, exact %.4f (rel. dev. %.4f); "
      "tau_d (paper's per-particle normalisation) = %.4f\n",
      *tau_std, exact, *tau_std / exact - 1.0, *tau_paper);
  CHECK(*tau_std == Approx(exact).epsilon(0.02));
  CHECK(*tau_paper == Approx(exact).epsilon(0.02));
}

TEST_CASE(
    "free active particles, tau_p = 250 >> tau_g: the paper's C_vv agrees with the closed "
    "form, tau_d",
    "[correlator][active][long]") {
  // The paper's slowest persistence (tau_p / tau_g = 50), where the velocity follows n.
  // 2000 particles in 10 groups, 20 tau_g of equilibration, 2000 time units sampled every
  // time unit; lags to t = 400, a new origin every 10. (8.4e7 particle steps: [long].)
  TimeCorrelatorParams p;
  p.lags = 401;
  p.origin_every = 10;
  p.sample_interval = 20 * kDt;
  p.position = false;
  const double tau_p = 250.0, tau_g = 1.0 / kGamma;
  const GroupCorrelators c = run_active(2000, tau_p, 0.02, 2000, 20, 2000, p, 0xC250ull);
  check_active(c, tau_p, 0.04, "paper's normalisation", &CorrelationFunctions::cvv);
  check_active(c, tau_p, 0.04, "standard normalisation", &CorrelationFunctions::cvv_standard);
  const CorrelationFunctions f = c.mean();
  const double exact = root([&](double t) { return active_vacf(t, tau_g, tau_p); }, kInvE, 1e4);
  const auto tau_std = decay_time(f.time, f.cvv_standard), tau_paper = decay_time(f.time, f.cvv);
  REQUIRE(tau_paper.has_value());
  REQUIRE(tau_std.has_value());
  std::printf(
      "[correlators] active tau_p = 250: tau_d (paper) = %.2f, (standard) = %.2f, exact %.2f\n",
      *tau_paper, *tau_std, exact);
  CHECK(*tau_paper == Approx(exact).epsilon(0.04));
  CHECK(*tau_std == Approx(exact).epsilon(0.04));
}

// =======================================================================================
// 3. Free Langevin particles: MSD and F_s against the exact results

TEST_CASE("free Langevin particles: MSD exact, F_s = exp(-k^2 MSD/6), tau_r, alpha_2 = 0",
          "[correlator][langevin]") {
  // kT = 2.5e-4 puts F_s(2 pi, t) = 1/e at t ~ 25. 1600 particles (10 groups) from Maxwell
  // velocities, 6 tau_g of equilibration, 600 time units sampled every 0.5; lags to t = 50,
  // a new origin every 4 time units. Both direction averages of F_s.
  const int n = 1600;
  const double kT = 2.5e-4;
  System sys = free_particles(n, 0x5EEDull);
  for (int i = 0; i < n; ++i)
    sys.sites().vel[i] =
        std::sqrt(kT) * RandomKey(sys.seed(), 0, std::uint32_t(i), RngStream::kVelocity).normal3();
  ForceField ff;
  Dynamics dyn(kDt);
  dyn.add(Method::langevin(all_sites(sys), kGamma, kT));
  dyn.run(sys, ff, 600);
  TimeCorrelatorParams p;
  p.lags = 101;
  p.origin_every = 8;
  p.sample_interval = 10 * kDt;
  p.velocity = p.orientation = false;
  TimeCorrelatorParams pyz = p;
  pyz.fs_average = FsAverage::kAxesYZ;
  GroupCorrelators iso(all_sites(sys), 10, p), yz(all_sites(sys), 10, pyz);
  for (int s = 0; s < 1200; ++s) {
    if (s > 0) dyn.run(sys, ff, 10);
    iso.sample(sys);
    yz.sample(sys);
  }
  const CorrelationFunctions f = iso.mean(), g = yz.mean();
  for (const auto* c : {&iso, &yz})
    for (const auto& group : c->groups) CHECK(group.result().fs[0] == 1.0);
  const double k2 = p.k * p.k;
  double worst_msd = 0, worst_disc = 0, worst_scheme = 0, worst_fs = 0, worst_gauss = 0,
         worst_a2 = 0;
  for (std::size_t i = 1; i < f.time.size(); ++i) {
    const double t = f.time[i], exact = langevin_msd(t, kT, kGamma);
    const double disc = langevin_msd_discrete(int(std::lround(t / kDt)), kT, kGamma, kDt);
    const double sigma = iso.error(&CorrelationFunctions::msd, i);
    INFO("t = " << t << ": MSD = " << f.msd[i] << " +- " << sigma << ", exact " << exact
                << ", scheme " << disc);
    CHECK(std::abs(f.msd[i] / exact - 1.0) < 0.02);
    CHECK(std::abs(f.msd[i] - disc) < 4.0 * sigma);
    worst_msd = std::max(worst_msd, std::abs(f.msd[i] / exact - 1.0));
    worst_disc = std::max(worst_disc, std::abs(f.msd[i] - disc) / sigma);
    worst_scheme = std::max(worst_scheme, std::abs(disc / exact - 1.0));
    // F_s: Gaussian displacements, so F_s = exp(-k^2 MSD / 6) for either direction average.
    for (const auto* h : {&f, &g}) {
      const double fs_exact = std::exp(-k2 * exact / 6.0),
                   fs_gauss = std::exp(-k2 * h->msd[i] / 6.0);
      INFO("F_s = " << h->fs[i] << ", exact " << fs_exact << ", from the measured MSD "
                    << fs_gauss);
      CHECK(std::abs(h->fs[i] - fs_exact) < 0.01);
      CHECK(std::abs(h->fs[i] - fs_gauss) < 0.005);
      worst_fs = std::max(worst_fs, std::abs(h->fs[i] - fs_exact));
      worst_gauss = std::max(worst_gauss, std::abs(h->fs[i] - fs_gauss));
    }
    CHECK(std::abs(f.alpha2[i]) < 0.03);
    worst_a2 = std::max(worst_a2, std::abs(f.alpha2[i]));
  }
  const double tau_r =
      root([&](double t) { return std::exp(-k2 * langevin_msd(t, kT, kGamma) / 6.0); }, kInvE, 1e3);
  const auto tau_iso = decay_time(f.time, f.fs), tau_yz = decay_time(g.time, g.fs);
  REQUIRE(tau_iso.has_value());
  REQUIRE(tau_yz.has_value());
  std::printf(
      "[correlators] Langevin kT = %g: MSD max rel. deviation from the continuous formula %.4f "
      "(the scheme's exact MSD differs by at most %.4f; measured vs scheme: max %.2f sigma); "
      "F_s max |dev| %.4f from exp(-k^2 MSD_exact/6), %.4f from exp(-k^2 MSD_measured/6); "
      "max |alpha_2| %.4f; tau_r = %.3f (isotropic), %.3f (y,z), exact %.3f\n",
      kT, worst_msd, worst_scheme, worst_disc, worst_fs, worst_gauss, worst_a2, *tau_iso, *tau_yz,
      tau_r);
  CHECK(*tau_iso == Approx(tau_r).epsilon(0.02));
  CHECK(*tau_yz == Approx(tau_r).epsilon(0.02));
  // The correlator's own tau_r on one group agrees with the interpolation of its F_s.
  const CorrelationFunctions g0 = iso.groups[0].result();
  REQUIRE(iso.groups[0].tau_r().has_value());
  CHECK(*iso.groups[0].tau_r() == *decay_time(g0.time, g0.fs));
}
