#include "integrate/dynamics.hpp"
#include "core/parallel.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <string>

#include "core/errors.hpp"
#include "core/fast_log.hpp"
#include "core/fast_trig.hpp"
#include "core/fused.hpp"
#include "core/rng.hpp"
#include "core/team_barrier.hpp"
#include "integrate/drift_lanes.hpp"
#include "integrate/engine_order.hpp"

namespace invasim {

void MethodParams::validate() const {
  require_non_negative("gamma", gamma);
  require_non_negative("kT", kT);
  require_non_negative("f0", f0);
  if (!(tau_p >= 0.0))
    fail_input("tau_p = ", tau_p, " must be >= 0 (0: uncorrelated, inf: frozen)");
}

Method::Method(std::vector<int> group, const MethodParams& params)
    : group_(std::move(group)), params_(params) {
  params_.validate();
}

std::shared_ptr<Method> Method::damped(std::vector<int> group, double gamma) {
  MethodParams p;
  p.gamma = gamma;
  return std::make_shared<Method>(std::move(group), p);
}

std::shared_ptr<Method> Method::langevin(std::vector<int> group, double gamma, double kT) {
  MethodParams p;
  p.gamma = gamma;
  p.kT = kT;
  return std::make_shared<Method>(std::move(group), p);
}

std::shared_ptr<Method> Method::active(std::vector<int> group, double gamma, double f0,
                                       double tau_p, double kT) {
  MethodParams p;
  p.gamma = gamma;
  p.f0 = f0;
  p.tau_p = tau_p;
  p.kT = kT;
  return std::make_shared<Method>(std::move(group), p);
}

namespace {
Vec3 uniform_on_sphere(double u0, double u1) {
  const double z = 2.0 * u0 - 1.0, rho = std::sqrt(std::max(0.0, 1.0 - z * z));
  double sin_phi, cos_phi;
  fast_trig::sincos(2.0 * M_PI * u1, sin_phi, cos_phi);
  return {rho * cos_phi, rho * sin_phi, z};
}

// n rotated by the angle theta about the axis at azimuth psi (angle 2 pi u_psi) in the plane
// perpendicular to n (frame from the axis n is least aligned with). Written so that the
// orientation pass below vectorises (the ifs become selects); the scalar rotate_orientation
// runs the same code. The sines and cosines come from fast_trig (within 2 ulp of libm's, one
// reduction per pair).
[[gnu::always_inline]] inline void rotate_by(double nx, double ny, double nz, double theta,
                                             double u_psi, double& ox, double& oy, double& oz) {
  const double ax = std::abs(nx), ay = std::abs(ny), az = std::abs(nz);
  // c = n x e_a for the least aligned axis a (ties as the scalar search: x, then y, then z).
  const bool use_y = ay < ax, use_z = az < (use_y ? ay : ax);
  double cx, cy, cz;
  if (use_z) {
    cx = ny, cy = -nx, cz = 0.0;  // n x e_z
  } else if (use_y) {
    cx = -nz, cy = 0.0, cz = nx;  // n x e_y
  } else {
    cx = 0.0, cy = nz, cz = -ny;  // n x e_x
  }
  // A site without an orientation (n = 0) keeps none: the reciprocal norms are taken as 0
  // there (as Eigen's normalized() leaves a zero vector), never inf.
  const double c2 = cx * cx + cy * cy + cz * cz;
  const double inv_c = c2 > 0.0 ? 1.0 / std::sqrt(c2) : 0.0;
  const double e1x = cx * inv_c, e1y = cy * inv_c, e1z = cz * inv_c;
  const double e2x = ny * e1z - nz * e1y, e2y = nz * e1x - nx * e1z, e2z = nx * e1y - ny * e1x;
  double sin_psi, cos_psi, sin_theta, cos_theta;
  fast_trig::sincos(2.0 * M_PI * u_psi, sin_psi, cos_psi);
  fast_trig::sincos(theta, sin_theta, cos_theta);
  const double wx = cos_psi * e1x + sin_psi * e2x, wy = cos_psi * e1y + sin_psi * e2y,
               wz = cos_psi * e1z + sin_psi * e2z;
  const double vx = cos_theta * nx + sin_theta * wx, vy = cos_theta * ny + sin_theta * wy,
               vz = cos_theta * nz + sin_theta * wz;
  const double v2 = vx * vx + vy * vy + vz * vz;
  const double inv_v = v2 > 0.0 ? 1.0 / std::sqrt(v2) : 0.0;
  ox = vx * inv_v, oy = vy * inv_v, oz = vz * inv_v;
}

// The Gaussian rotation angle of variance 2 dt / tau_p from two uniforms (Box-Muller).
[[gnu::always_inline]] inline double rotation_angle(double scale, double log_u0, double u1) {
  return scale * std::sqrt(-2.0 * log_u0) * fast_trig::cos(2.0 * M_PI * u1);
}
}  // namespace

Vec3 rotate_orientation(const Vec3& n, double dt, double tau_p, const std::array<double, 4>& u) {
  if (tau_p == 0.0) return uniform_on_sphere(u[0], u[1]);
  if (std::isinf(tau_p)) return n;
  const double theta = rotation_angle(std::sqrt(2.0 * dt / tau_p), fast_log::log(u[0]), u[1]);
  Vec3 out;
  rotate_by(n.x(), n.y(), n.z(), theta, u[2], out.x(), out.y(), out.z());
  return out;
}

GroupSlots GroupSlots::of(const System& sys, const std::vector<int>& group) {
  GroupSlots g;
  g.slot.reserve(group.size());
  for (int i : group) g.slot.push_back(sys.slot_of(i));
  std::sort(g.slot.begin(), g.slot.end());
  g.site.reserve(group.size());
  for (int k : g.slot) g.site.push_back(sys.site_of_slot(k));
  return g;
}

void Method::randomize_orientations(System& sys, std::uint64_t stream_step) const {
  auto& s = sys.sites();
  for (int i : group_) {
    const auto u =
        RandomKey(sys.seed(), stream_step, std::uint32_t(i), RngStream::kOrientation, 1).uniform4();
    s.orient[sys.slot_of(i)] = uniform_on_sphere(u[0], u[1]);
  }
}

namespace {
using integrate_detail::WrapBounds;

// The drift of the slots [lo, hi): the half kick, the move and the zeroed force, whole blocks of
// 8 sites in vector lanes (drift_lanes.hpp) and the rest in the scalar loop, then the wrap only
// for the few sites that left the box on a periodic axis. Every drift goes through this
// function, whatever the runs a thread's share is cut into, and its multiply-adds are explicit
// (core/fused.hpp): a site's bits then do not depend on whether it falls in a vector lane or
// the scalar loop, so not on the thread count.
void drift_range(Sites& s, const Box& box, const WrapBounds& bounds, int lo, int hi, double dt) {
  static_assert(sizeof(Vec3) == 3 * sizeof(double), "sites' vectors are read as flat arrays");
  double* __restrict v = s.vel.data()->data();
  double* __restrict x = s.pos.data()->data();
  double* __restrict f = s.force.data()->data();
  const double* __restrict m = s.mass.data();
  const double *blo = bounds.lo, *bhi = bounds.hi;
  int outside = 0;
  int first = lo;
#if INVASIM_DRIFT_LANES
  first = integrate_detail::drift_blocks_lanes(v, x, f, m, bounds, lo, hi, dt, outside);
#endif
  for (int i = first; i < hi; ++i) {
    const double h = 0.5 * dt / m[i];
    int out = 0;
    for (int a = 0; a < 3; ++a) {
      const int k = 3 * i + a;
      v[k] = mul_add(h, f[k], v[k]);
      x[k] = mul_add(dt, v[k], x[k]);
      f[k] = 0.0;
      out |= !(x[k] >= blo[a] && x[k] < bhi[a]);  // (a NaN counts as outside, as in wrap)
    }
    outside |= out;
  }
  if (outside)
    for (int i = lo; i < hi; ++i) box.wrap(s.pos[i], s.image[i]);
}

// The drift of the slots slot[0, n): runs of consecutive slots (a method's group is one run in
// the engine order unless sites of no method sit between its own) in drift_range's lanes.
void drift_slot_list(Sites& s, const Box& box, const int* slot, int n, double dt) {
  const WrapBounds bounds(box);
  for (int k = 0; k < n;) {
    int e = k + 1;
    while (e < n && slot[e] == slot[e - 1] + 1) ++e;
    drift_range(s, box, bounds, slot[k], slot[k] + (e - k), dt);
    k = e;
  }
}
}  // namespace

void Method::drift_team(System& sys, double dt, const GroupSlots& slots) const {
  Sites& s = sys.sites();
  const Box& box = sys.box();
  const int n = int(slots.slot.size());
  // Blocks of slots, statically over the team (each site's drift is independent).
  constexpr int kBlock = 256;
  const int blocks = (n + kBlock - 1) / kBlock;
#pragma omp for schedule(static) nowait
  for (int b = 0; b < blocks; ++b)
    drift_slot_list(s, box, slots.slot.data() + b * kBlock, std::min(kBlock, n - b * kBlock), dt);
}

void Method::drift_slots(System& sys, double dt, const std::vector<int>& slots) const {
  drift_slot_list(sys.sites(), sys.box(), slots.data(), int(slots.size()), dt);
}

namespace {
// Damping, thermal noise and self-propulsion on site i at the system's current step.
// g: the site's standard normal thermal draw (read only when noise > 0).
inline Vec3 drive_force(const MethodParams& p, double noise, const Sites& s, int i, const Vec3& g) {
  Vec3 f = -p.gamma * s.vel[i];
  if (noise > 0.0) f += noise * g;
  if (p.f0 > 0.0) f += p.f0 * s.orient[i];
  return f;
}
// Standard deviation of the per-component random force (fluctuation-dissipation).
inline double noise_amplitude(const MethodParams& p, double dt) {
  return p.kT > 0.0 ? std::sqrt(2.0 * p.gamma * p.kT / dt) : 0.0;
}
}  // namespace

void Method::add_drive(System& sys, double dt, const GroupSlots& slots) const {
  Sites& s = sys.sites();
  const double noise = noise_amplitude(params_, dt);
  const std::uint64_t seed = sys.seed(), step = sys.step;
  const int n = int(slots.slot.size());
#pragma omp parallel for schedule(static) if (parallel_light(std::size_t(n)))
  for (int k = 0; k < n; ++k) {
    const int i = slots.slot[k];
    const Vec3 g =
        noise > 0.0
            ? RandomKey(seed, step, std::uint32_t(slots.site[k]), RngStream::kThermal).normal3()
            : Vec3::Zero();
    s.force[i] += drive_force(params_, noise, s, i, g);
  }
}

namespace {
constexpr int kKickChunk = Method::kKickChunk;
static_assert(kKickChunk <= RandomKey::kBatch, "a kick chunk's thermal draws are one batch");

// The orientation update of the cells in slots idx[0, m), m <= kKickChunk, of permanent indices
// site[0, m), at `step`: each cell's Philox block, the logarithms (core/fast_log.hpp), then the
// rotations, in loops the compiler vectorises (the per-cell scalar version, with libm's sin,
// cos and log, was ~20 % of an active run).
void rotate_chunk(Sites& s, const int* idx, const int* site, int m, double dt, double tau_p,
                  std::uint64_t seed, std::uint64_t step) {
  if (tau_p == 0.0 || std::isinf(tau_p)) {  // redrawn or frozen: no rotation to vectorise
    for (int q = 0; q < m; ++q) {
      const int i = idx[q];
      const auto u =
          RandomKey(seed, step, std::uint32_t(site[q]), RngStream::kOrientation).uniform4();
      s.orient[i] = rotate_orientation(s.orient[i], dt, tau_p, u);
    }
    return;
  }
  // Structure of arrays for the vector loops: the uniforms, then the orientations.
  double u0[kKickChunk], u1[kKickChunk], u2[kKickChunk], lg[kKickChunk];
  double nx[kKickChunk], ny[kKickChunk], nz[kKickChunk];
#pragma omp simd
  for (int q = 0; q < m; ++q) {
    std::uint32_t w0, w1, w2, w3;
    RandomKey::block_words(seed, step, std::uint32_t(site[q]), RngStream::kOrientation, w0, w1, w2,
                           w3);
    u0[q] = RandomKey::uniform(w0), u1[q] = RandomKey::uniform(w1), u2[q] = RandomKey::uniform(w2);
  }
#pragma omp simd
  for (int q = 0; q < m; ++q) lg[q] = fast_log::log(u0[q]);
  for (int q = 0; q < m; ++q) {
    const Vec3& n = s.orient[idx[q]];
    nx[q] = n.x(), ny[q] = n.y(), nz[q] = n.z();
  }
  const double scale = std::sqrt(2.0 * dt / tau_p);
#pragma omp simd
  for (int q = 0; q < m; ++q)
    rotate_by(nx[q], ny[q], nz[q], rotation_angle(scale, lg[q], u1[q]), u2[q], nx[q], ny[q], nz[q]);
  for (int q = 0; q < m; ++q) s.orient[idx[q]] = Vec3(nx[q], ny[q], nz[q]);
}
}  // namespace

void Method::kick_chunk(System& sys, double dt, std::uint64_t step, const MethodParams& p,
                        const GroupSlots& slots, int c) const {
  Sites& s = sys.sites();
  const double noise = noise_amplitude(p, dt);
  const std::uint64_t seed = sys.seed();
  const int n = int(slots.slot.size());
  const int* slot = slots.slot.data();
  const int* site = slots.site.data();
  const int lo = c * kKickChunk, hi = std::min(n, lo + kKickChunk);
  if (p.f0 > 0.0) rotate_chunk(s, slot + lo, site + lo, hi - lo, dt, p.tau_p, seed, step);
  // The chunk's thermal draws in vector lanes (normal3's numbers).
  double g[3][RandomKey::kBatch];
  if (noise > 0.0) RandomKey::normal3_batch(seed, step, site + lo, hi - lo, RngStream::kThermal, g);
  for (int k = lo; k < hi; ++k) {
    const int i = slot[k];
    const Vec3 gk = noise > 0.0 ? Vec3(g[0][k - lo], g[1][k - lo], g[2][k - lo]) : Vec3::Zero();
    s.force[i] += drive_force(p, noise, s, i, gk);
    s.vel[i] += 0.5 * dt / s.mass[i] * s.force[i];
  }
}

int Method::kick_chunks(const GroupSlots& slots) {
  return int((slots.slot.size() + kKickChunk - 1) / kKickChunk);
}

void Method::kick_team(System& sys, double dt, std::uint64_t step, const MethodParams& p,
                       const GroupSlots& slots) const {
  const int chunks = kick_chunks(slots);
  // Dynamic: the random numbers make this the heaviest of the light loops, and a thread
  // slowed by another process on its core takes fewer chunks.
#pragma omp for schedule(dynamic, 1) nowait
  for (int c = 0; c < chunks; ++c) kick_chunk(sys, dt, step, p, slots, c);
}

namespace {

// A time step must be finite and > 0: an infinite one (dyn:set_dt(math.huge)) would turn the
// next step's positions into inf/NaN.
void require_time_step(double dt) {
  require_positive("dt", dt);
  if (!std::isfinite(dt)) fail_input("dt = ", dt, " must be finite (in (0, inf))");
}

}  // namespace

Dynamics::Dynamics(double dt) : dt_(dt) {
  require_time_step(dt);
}

void Dynamics::sites_changed(const SiteChange& change) {
  if (change.empty()) return;
  for (const auto& m : methods_) m->set_group(change.follow(m->group()));
  slots_valid_ = false;
  prepared_ = false;
}

void Dynamics::set_dt(double dt) {
  require_time_step(dt);
  // The same step keeps the prepared forces: preparing them again would evaluate the next
  // step's damping with the full-step velocity, not the half-step one, and a script that sets
  // the step it already has (a second quench) would leave the trajectory it continues.
  if (dt == dt_) return;
  dt_ = dt;
  prepared_ = false;
}

namespace {
// Installs a ramp of a non-negative parameter (`name`), which starts at its 'from' value.
void set_non_negative_ramp(const char* name, std::optional<Ramp> ramp, double& value,
                           std::optional<Ramp>& slot) {
  if (ramp) {
    ramp->validate(name);
    require_non_negative((std::string(name) + " ramp 'from'").c_str(), ramp->from);
    require_non_negative((std::string(name) + " ramp 'to'").c_str(), ramp->to);
    value = ramp->from;
  }
  slot = std::move(ramp);
}
}  // namespace

void Method::set_kT_ramp(std::optional<Ramp> ramp) {
  set_non_negative_ramp("kT", std::move(ramp), params_.kT, kT_ramp_);
}

void Method::set_f0_ramp(std::optional<Ramp> ramp) {
  set_non_negative_ramp("f0", std::move(ramp), params_.f0, f0_ramp_);
}

MethodParams Method::params_at(std::uint64_t step) {
  MethodParams p = params_;
  if (kT_ramp_) p.kT = kT_ramp_->value(step);
  if (f0_ramp_) p.f0 = f0_ramp_->value(step);
  return p;
}

void Method::apply_ramps(std::uint64_t step) {
  params_ = params_at(step);
}

void Dynamics::apply_ramps(std::uint64_t step) {
  for (const auto& m : methods_) m->apply_ramps(step);
  if (wall_ && wall_->pressure_ramp) wall_->pressure = wall_->pressure_ramp->value(step);
}

void Dynamics::set_sort_every(std::uint64_t n) {
  if (n < 1) fail_input("sort_every = ", n, " must be >= 1 step");
  sort_every_ = n;
}

void Dynamics::prepare(System& sys, ForceField& ff) {
  slots_valid_ = false;  // (sync_slots checks the groups)
  sync_slots(sys);
  if (wall_) wall_->validate();
  apply_ramps(sys.step);
  ff.compute(sys);
  for (std::size_t k = 0; k < methods_.size(); ++k) methods_[k]->add_drive(sys, dt_, slots_[k]);
  if (wall_) wall_->update_force(sys, dt_);
  prepared_ = true;
}

void Dynamics::sync_slots(const System& sys) {
  if (slots_valid_ && slots_n_ == sys.n_sites() && slots_layout_ == sys.layout_id()) return;
  // The groups must be disjoint (the drift of different groups runs concurrently).
  std::vector<char> owned(sys.n_sites(), 0);
  for (const auto& m : methods_)
    for (int i : m->group()) {
      if (i < 0 || std::size_t(i) >= sys.n_sites())
        fail_input("integrator: site ", i, " of a group is outside [0, ", sys.n_sites(), ")");
      if (owned[i]++) fail_input("integrator: site ", i, " belongs to two integration methods");
    }
  slots_.clear();
  for (const auto& m : methods_) slots_.push_back(GroupSlots::of(sys, m->group()));
  free_sites_.clear();
  for (std::size_t i = 0; i < owned.size(); ++i)
    if (!owned[i]) free_sites_.push_back(sys.slot_of(int(i)));
  std::sort(free_sites_.begin(), free_sites_.end());
  slots_n_ = sys.n_sites();
  slots_layout_ = sys.layout_id();
  slots_valid_ = true;
  ++slots_version_;
}

void Dynamics::begin_step_serial(System& sys) {
  // The piston's half kick and move first: the sites' drift does not read the wall (it wraps
  // periodic axes only), and a failing move (Box refuses it) throws before any site moved.
  if (wall_) {
    wall_->half_kick(dt_);
    wall_->move(sys.box(), dt_);
  }
  // A new engine order at every multiple of sort_every (a function of the step and the state).
  if (sys.engine_layout() && sys.step % sort_every_ == 0) sys.set_engine_order(spatial_order(sys));
  sync_slots(sys);
  grow_to_team(thread_slots_);
  next_step_ = sys.step + 1;
  next_params_.clear();
  for (const auto& m : methods_) next_params_.push_back(m->params_at(next_step_));
}

namespace {
// Every method's slots owned by the kernel's threads below t, for t = 0 .. team (in the engine
// order a method's slots run along the kernel's slab axis, so these are (nearly) prefixes):
// the start of balanced_cuts.
std::vector<std::vector<int>> owned_below(const std::vector<GroupSlots>& slots,
                                          const std::vector<int>& owner, int team) {
  std::vector<std::vector<int>> cuts(slots.size(), std::vector<int>(std::size_t(team) + 1, 0));
  for (std::size_t k = 0; k < slots.size(); ++k) {
    std::vector<int>& c = cuts[k];
    for (int i : slots[k].slot) ++c[std::size_t(owner[std::size_t(i)]) + 1];
    for (std::size_t t = 1; t < c.size(); ++t) c[t] += c[t - 1];
  }
  return cuts;
}

// Cuts of every method's slots between the team's threads (thread t takes slots
// [cuts[k][t], cuts[k][t + 1]) of method k) that balance cost[k] per slot, from the kernel's
// owners (`cuts`, owned_below): each cut moves, in every method by the method's share of its
// size, until the cost below it is t / team of the whole, so only the slots nearest the
// kernel's cut change thread and few sites are drifted or kicked away from the core that
// computed their forces. Any cuts give the same results.
std::vector<std::vector<int>> balanced_cuts(std::vector<std::vector<int>> cuts,
                                            const std::vector<GroupSlots>& slots,
                                            const std::vector<double>& cost) {
  const std::size_t methods = slots.size();
  const std::size_t parts = methods > 0 ? cuts[0].size() - 1 : 0;
  double total = 0.0;
  for (std::size_t k = 0; k < methods; ++k) total += cost[k] * double(slots[k].slot.size());
  if (!(total > 0.0)) return cuts;
  for (std::size_t t = 1; t < parts; ++t) {
    double below = 0.0;
    for (std::size_t k = 0; k < methods; ++k) below += cost[k] * double(cuts[k][t]);
    const double shift = (total * double(t) / double(parts) - below) / total;
    for (std::size_t k = 0; k < methods; ++k) {
      const int n = int(slots[k].slot.size());
      const int moved = int(std::lround(double(cuts[k][t]) + shift * double(n)));
      cuts[k][t] = std::clamp(moved, cuts[k][t - 1], n);
    }
  }
  return cuts;
}
}  // namespace

void Dynamics::drift_own_sites(System& sys, const ForceField& ff) {
  std::uint64_t version = 0;
  int parts = 0;
  const std::vector<int>* owner = ff.site_owner(version, parts);
  const int team = omp_get_num_threads(), me = omp_get_thread_num();
  // Every thread of the team takes the same branch (the same owner, version and sizes).
  if (!owner || team < 2 || parts != team || owner->size() != sys.n_sites() ||
      std::size_t(me) >= thread_slots_.size()) {
    if (std::size_t(me) < thread_slots_.size()) thread_slots_[std::size_t(me)].active = false;
    for (std::size_t k = 0; k < methods_.size(); ++k) methods_[k]->drift_team(sys, dt_, slots_[k]);
    return;
  }
  ThreadSlots& mine = thread_slots_[std::size_t(me)];
  if (mine.partition != version || mine.slots != slots_version_) {
    // The drift costs the same per site; the kick of an active method (its rotations) about
    // twice that of a thermal one.
    std::vector<double> drift_cost(methods_.size(), 1.0), kick_cost(methods_.size(), 1.0);
    for (std::size_t k = 0; k < methods_.size() && k < next_params_.size(); ++k)
      if (next_params_[k].f0 > 0.0) kick_cost[k] = 2.0;
    const auto owned = owned_below(slots_, *owner, team);
    const auto drift_cuts = balanced_cuts(owned, slots_, drift_cost);
    const auto kick_cuts = balanced_cuts(owned, slots_, kick_cost);
    mine.of_method.resize(methods_.size());
    mine.chunks_of_method.resize(methods_.size());
    for (std::size_t k = 0; k < methods_.size(); ++k) {
      const std::vector<int>& slot = slots_[k].slot;
      const int lo = drift_cuts[k][std::size_t(me)], hi = drift_cuts[k][std::size_t(me) + 1];
      mine.of_method[k].assign(slot.begin() + lo, slot.begin() + hi);
      // A kick chunk goes to the thread whose kick cuts hold its first slot.
      mine.chunks_of_method[k].clear();
      for (int c = 0; c < Method::kick_chunks(slots_[k]); ++c) {
        const int first = c * Method::kKickChunk;
        if (first >= kick_cuts[k][std::size_t(me)] && first < kick_cuts[k][std::size_t(me) + 1])
          mine.chunks_of_method[k].push_back(c);
      }
    }
    mine.partition = version;
    mine.slots = slots_version_;
  }
  mine.active = true;
  for (std::size_t k = 0; k < methods_.size(); ++k)
    methods_[k]->drift_slots(sys, dt_, mine.of_method[k]);
}

void Dynamics::kick_own_sites(System& sys) {
  const int me = omp_get_thread_num();
  // The drift of this step chose for all threads alike (drift_own_sites).
  if (omp_get_num_threads() > 1 && std::size_t(me) < thread_slots_.size() &&
      thread_slots_[std::size_t(me)].active) {
    const ThreadSlots& mine = thread_slots_[std::size_t(me)];
    for (std::size_t k = 0; k < methods_.size(); ++k)
      for (int c : mine.chunks_of_method[k])
        methods_[k]->kick_chunk(sys, dt_, next_step_, next_params_[k], slots_[k], c);
    return;
  }
  for (std::size_t k = 0; k < methods_.size(); ++k)
    methods_[k]->kick_team(sys, dt_, next_step_, next_params_[k], slots_[k]);
}

TeamHooks Dynamics::step_hooks(System& sys, const ForceField& ff) {
  // Drift and kick run inside the force field's parallel region (docs/performance.md
  // "The parallel step"), not in regions of their own.
  TeamHooks hooks;
  // The drift zeroes the forces of its sites; the sites of no method are zeroed alongside.
  hooks.zeroes_forces = true;
  hooks.before = [this, &sys, &ff] {
    drift_own_sites(sys, ff);
    auto& f = sys.sites().force;
    const int n_free = int(free_sites_.size());
#pragma omp for schedule(static) nowait
    for (int k = 0; k < n_free; ++k) f[free_sites_[k]].setZero();
  };
  hooks.after = [this, &sys] { kick_own_sites(sys); };
  return hooks;
}

void Dynamics::end_step_serial(System& sys) {
  ++sys.step;
  sys.time += dt_;
  apply_ramps(sys.step);
  if (wall_) {
    wall_->update_force(sys, dt_);
    wall_->half_kick(dt_);
  }
}

void Dynamics::step(System& sys, ForceField& ff) {
  const EngineLayoutScope layout(sys);
  if (!prepared_) prepare(sys, ff);
  // 1 thread or all, as measured to be faster (integrate/step_threads.hpp); same results.
  const ThreadCountScope threads(step_threads_.begin_step());
  const auto start = std::chrono::steady_clock::now();
  begin_step_serial(sys);
  ff.compute(sys, {}, nullptr, step_hooks(sys, ff));
  end_step_serial(sys);
  step_threads_.end_step(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

std::uint64_t Dynamics::run_team(System& sys, ForceField& ff, std::uint64_t max_steps,
                                 int threads) {
  using Clock = std::chrono::steady_clock;
  const TeamHooks hooks = step_hooks(sys, ff);
  std::uint64_t done = 0;
  std::exception_ptr error;
  // The leader's two decisions per step, each read by every thread after the barrier that
  // follows it. Two flags, not one: the leader takes its next decision right after that
  // barrier, possibly before a slower thread has read the previous one.
  bool prepared = true, go_on = true;
  int team_size = 1;  // the threads OpenMP gave the region (fewer than asked under a limit)
  Clock::time_point start;
  ++team_regions_;
#pragma omp parallel num_threads(threads)
  {
    if (team_leader()) team_size = omp_get_num_threads();
    for (;;) {
      // A step's serial parts run on the leader while the others wait at the team barrier;
      // they may throw, so the leader ends the loop for all and the error leaves the region.
      if (team_leader()) {
        try {
          start = Clock::now();
          begin_step_serial(sys);
          ff.prepare_team_step(sys, {});
        } catch (...) {
          error = std::current_exception();
          prepared = false;
        }
      }
      team_barrier();
      if (!prepared) break;
      ff.compute_team(sys, {}, hooks);
      team_barrier();
      if (team_leader()) {
        try {
          end_step_serial(sys);
          step_threads_.end_step(std::chrono::duration<double>(Clock::now() - start).count());
          ++done;
          if (blowup_guard_.due(sys.step)) check_blowup(sys);
          // Go on while the measured choice keeps the team (it may measure 1 thread next).
          go_on = done < max_steps && step_threads_.begin_step() == threads;
        } catch (...) {
          error = std::current_exception();
          go_on = false;
        }
      }
      team_barrier();
      if (!go_on) break;
    }
  }
  if (team_size > 1) parallel_steps_ += done;
  if (error) std::rethrow_exception(error);
  return done;
}

void Dynamics::run(System& sys, ForceField& ff, std::uint64_t n_steps) {
  const EngineLayoutScope layout(sys);
  // The initial forces first (as step() would), so that the first step can run in the team too.
  if (n_steps > 0 && !prepared_) prepare(sys, ff);
  std::uint64_t k = 0;
  while (k < n_steps) {
    // Consecutive team steps share one parallel region (docs/performance.md "Team steps and the
    // barrier"). (The thread choice first: while it keeps one thread, a step asks nothing else.)
    if (prepared_) {
      const int threads = step_threads_.begin_step();
      if (threads > 1 && parallel_team(sys.n_sites()) && ff.supports_team()) {
        k += run_team(sys, ff, n_steps - k, threads);
        continue;
      }
    }
    step(sys, ff);
    ++k;
    if (blowup_guard_.due(sys.step)) check_blowup(sys);
  }
  if (n_steps > 0 && !blowup_guard_.due(sys.step)) check_blowup(sys);
}

}  // namespace invasim
