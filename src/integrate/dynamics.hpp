#pragma once
// Time stepping (docs/model.md, "Equations of motion"): the paper's modified velocity Verlet, in
// which damping -gamma v and the random / active drive enter with the half-step velocity:
//   v_h = v + dt/2 F/m;  x += v_h dt;  F = F_cons(x) - gamma v_h + F_drive;  v = v_h + dt/2 F/m.
// A Dynamics owns one time step dt and a list of methods, each moving one group of sites:
// Damped (adipocyte vertices), Langevin (passive cells, FDT noise) or Active (self-propulsion
// f0 n with exact rotational diffusion, optional thermal noise). An optional PressureWall
// moves the left wall under a target pressure. Sites in no method do not move.
#include <limits>
#include <memory>
#include <vector>

#include "forces/force.hpp"
#include "integrate/blowup_guard.hpp"
#include "integrate/pressure_wall.hpp"
#include "integrate/proliferation.hpp"
#include "integrate/ramp.hpp"
#include "integrate/step_threads.hpp"

namespace invasim {

struct MethodParams {
  double gamma = 0.2;                                      // damping coefficient (force = -gamma v)
  double kT = 0.0;                                         // thermal noise temperature (0: none)
  double f0 = 0.0;                                         // self-propulsion force (0: passive)
  double tau_p = std::numeric_limits<double>::infinity();  // persistence time (0: white)
  void validate() const;
};

// A group's sites in the System's current storage layout (System::layout_id): their storage
// slots in increasing order and, for each, its permanent index, which keys its random numbers
// (so that they do not depend on the layout).
struct GroupSlots {
  std::vector<int> slot, site;
  static GroupSlots of(const System& sys, const std::vector<int>& group);
};

// One group of sites and how it moves.
class Method {
 public:
  Method(std::vector<int> group, const MethodParams& params);
  static std::shared_ptr<Method> damped(std::vector<int> group, double gamma);
  static std::shared_ptr<Method> langevin(std::vector<int> group, double gamma, double kT);
  static std::shared_ptr<Method> active(std::vector<int> group, double gamma, double f0,
                                        double tau_p, double kT = 0.0);

  const std::vector<int>& group() const { return group_; }
  // A new list of sites (when cells were born or died: Dynamics::sites_changed); a checkpoint
  // then stores the list (group_changed()), which a restored run takes instead of its own.
  void set_group(std::vector<int> group) {
    group_ = std::move(group);
    group_changed_ = true;
  }
  bool group_changed() const { return group_changed_; }
  const MethodParams& params() const { return params_; }
  MethodParams& params() { return params_; }
  // Optional linear ramps of kT and f0 (applied at every step by the Dynamics); setting a
  // number through params() does not clear a ramp, set_*_ramp({}) does.
  void set_kT_ramp(std::optional<Ramp> ramp);
  void set_f0_ramp(std::optional<Ramp> ramp);
  const std::optional<Ramp>& kT_ramp() const { return kT_ramp_; }
  const std::optional<Ramp>& f0_ramp() const { return f0_ramp_; }
  // Sets kT and f0 from their ramps for time step `step` (no-op without ramps).
  void apply_ramps(std::uint64_t step);
  // The parameters apply_ramps(step) would set, without setting them (a ramp used for the
  // first time is anchored at `step`, as apply_ramps would).
  MethodParams params_at(std::uint64_t step);
  // Gives every site of the group a random orientation (for active methods), keyed by its
  // permanent index.
  void randomize_orientations(System& sys, std::uint64_t stream_step = 0) const;

  // The two halves of a step, called by every thread of a parallel region (ForceField's
  // TeamHooks): the group's sites (`slots`: this group in the current layout) shared with an
  // orphaned `omp for nowait` (groups of different methods are disjoint), so the caller adds
  // the barrier.
  // v_h = v + dt/2 F/m; x += v_h dt (positions wrapped); then F = 0 (the next evaluation adds
  // into it).
  void drift_team(System& sys, double dt, const GroupSlots& slots) const;
  // The same drift on the given slots only (a thread's share, by the force field's site
  // owners), without worksharing.
  void drift_slots(System& sys, double dt, const std::vector<int>& slots) const;
  // Orientation update and drive of step `step` with parameters p; then v = v_h + dt/2 F/m.
  // In chunks of kKickChunk slots, fixed so that the SIMD lane a cell's orientation update
  // runs in (and so its rounding) does not depend on the number of threads: kick_team shares
  // them with an orphaned `omp for nowait`, kick_chunk does chunk c alone.
  static constexpr int kKickChunk = 128;
  static int kick_chunks(const GroupSlots& slots);
  void kick_team(System& sys, double dt, std::uint64_t step, const MethodParams& p,
                 const GroupSlots& slots) const;
  void kick_chunk(System& sys, double dt, std::uint64_t step, const MethodParams& p,
                  const GroupSlots& slots, int c) const;
  // Adds -gamma v + drive to the site forces (used to start a run from the current v).
  void add_drive(System& sys, double dt, const GroupSlots& slots) const;

 private:
  std::vector<int> group_;
  bool group_changed_ = false;
  MethodParams params_;
  std::optional<Ramp> kT_ramp_, f0_ramp_;
};

// Rotates unit vector n about a uniformly random axis perpendicular to it by a Gaussian
// angle of variance 2 dt / tau_p, so E[n'.n] = exp(-dt/tau_p) for any dt (u: 4 uniforms).
Vec3 rotate_orientation(const Vec3& n, double dt, double tau_p, const std::array<double, 4>& u);

class Dynamics {
 public:
  explicit Dynamics(double dt);
  double dt() const { return dt_; }
  // A new time step; the forces are prepared again before the next step (the same step: no-op).
  void set_dt(double dt);
  void add(std::shared_ptr<Method> method) {
    methods_.push_back(std::move(method));
    slots_valid_ = false;
  }
  const std::vector<std::shared_ptr<Method>>& methods() const { return methods_; }
  void set_pressure_wall(std::shared_ptr<PressureWall> wall) { wall_ = std::move(wall); }
  std::shared_ptr<PressureWall> pressure_wall() const { return wall_; }

  // Evaluates forces and drive at the current state so that stepping can start; step() and
  // run() call it once when forces are stale (after construction or a state change).
  void prepare(System& sys, ForceField& ff);
  void invalidate() { prepared_ = false; }
  // After cells were born or died (Proliferation): every method's group follows its cells
  // (SiteChange::follow: a daughter joins its parent's method), and the next step re-prepares.
  void sites_changed(const SiteChange& change);
  // Declares the site forces current (restored from a checkpoint together with the state they
  // belong to), so that the next step does not re-evaluate them: a restored run then
  // continues bit for bit like one that was never interrupted.
  void mark_prepared() { prepared_ = true; }
  bool prepared() const { return prepared_; }
  // One time step.
  void step(System& sys, ForceField& ff);
  // n_steps steps, checked for a blow-up (integrate/blowup_guard.hpp) every check_every()
  // steps and at the end; throws SimulationError naming the first blown-up site.
  void run(System& sys, ForceField& ff, std::uint64_t n_steps);
  std::uint64_t check_every() const { return blowup_guard_.every(); }
  // How many threads each step uses (integrate/step_threads.hpp): measured by default.
  StepThreads& step_threads() { return step_threads_; }
  const StepThreads& step_threads() const { return step_threads_; }
  void set_check_every(std::uint64_t n) { blowup_guard_.set_every(n); }
  // The steps store the sites in the engine order (integrate/engine_order.hpp, System's
  // layouts), chosen again before every step that starts at a multiple of sort_every() (and
  // when the sites have none: on the first step after sites were added), so that the order,
  // and with it every sum, is a function of the step and the state: a run restarted from a
  // checkpoint (which stores the order) continues bit for bit.
  std::uint64_t sort_every() const { return sort_every_; }
  void set_sort_every(std::uint64_t n);
  // Parallel regions opened by run() for runs of team steps (each holds consecutive steps that
  // use all threads; for tests and benchmarks).
  std::uint64_t team_regions() const { return team_regions_; }
  // Steps run inside those regions by more than one thread, since construction (steps run by
  // step() alone are not counted, though their force loops may use the threads).
  std::uint64_t parallel_steps() const { return parallel_steps_; }

 private:
  void apply_ramps(std::uint64_t step);
  // A step's parts: the serial one before the forces (piston, the methods' parameters for the
  // step), the drift and kick as the force field's hooks (every thread of the team), the
  // serial one after (step count, ramps, piston force).
  void begin_step_serial(System& sys);
  TeamHooks step_hooks(System& sys, const ForceField& ff);
  // The drift and the kick of the calling thread of the team: its share of every method's
  // slots where the force field partitions the sites for this team (ForceField::site_owner),
  // else the methods' shared loops. The shares start from the kernel's owners and move the
  // slots nearest its cut until the drift's count and the kick's cost are even (balanced_cuts
  // in dynamics.cpp; the kick by whole chunks). Any share gives the same results; these keep
  // most sites' data in the cache of the core that computed their forces.
  void drift_own_sites(System& sys, const ForceField& ff);
  void kick_own_sites(System& sys);
  void end_step_serial(System& sys);
  // Up to max_steps steps with `threads` threads in one parallel region, while the measured
  // choice keeps the team; returns the steps made (at least 1, or throws).
  std::uint64_t run_team(System& sys, ForceField& ff, std::uint64_t max_steps, int threads);
  double dt_;
  std::vector<std::shared_ptr<Method>> methods_;
  std::shared_ptr<PressureWall> wall_;
  bool prepared_ = false;
  BlowupGuard blowup_guard_;
  StepThreads step_threads_;
  std::vector<MethodParams> next_params_;  // each method's parameters for the step being made
  std::uint64_t next_step_ = 0;            // the number of the step being made
  std::uint64_t team_regions_ = 0;
  std::uint64_t parallel_steps_ = 0;
  // The methods' groups and the sites in no method (their forces are zeroed next to the drift)
  // as storage slots, for the layout slots_layout_ of slots_n_ sites.
  void sync_slots(const System& sys);
  std::vector<GroupSlots> slots_;
  std::vector<int> free_sites_;
  std::uint64_t slots_layout_ = 0;
  std::size_t slots_n_ = 0;
  bool slots_valid_ = false;
  std::uint64_t slots_version_ = 0;  // incremented whenever sync_slots rebuilds slots_
  // Each thread's share of every method's slots for the drift, for one site partition and
  // one version of slots_ (rebuilt by the thread itself when either changed).
  struct ThreadSlots {
    std::uint64_t partition = ~std::uint64_t(0), slots = ~std::uint64_t(0);
    std::vector<std::vector<int>> of_method, chunks_of_method;
    bool active = false;  // this step's drift used these shares (so does its kick)
  };
  std::vector<ThreadSlots> thread_slots_;
  std::uint64_t sort_every_ = 1000;
};

}  // namespace invasim
