#pragma once
// FIRE energy minimiser (Bitzek et al. 2006, with the FIRE 2.0 refinements of Guenole et al.
// 2020: semi-implicit Euler, half-step back-off on uphill moves, delayed dt growth). All sites
// move; when a PressureWall is given the left wall is one more degree of freedom whose force
// is the site reaction plus P A, so the minimiser finds mechanical equilibrium at pressure P
// (its inertia there is m A / d^2, one layer of mean sites, or the wall's mass if larger).
// Converged when every site force is below ftol and the wall's net force per unit area is
// below ftol.
#include <cstdint>
#include <functional>
#include <optional>

#include "integrate/dynamics.hpp"

namespace invasim {

struct FireParams {
  double ftol = 1e-8;    // max force per site at convergence
  double dt = 0.05;      // initial time step
  double dt_max = 0.5;   // largest time step
  double dt_min = 1e-6;  // smallest time step before giving up shrinking
  std::uint64_t max_steps = 1000000;
  double alpha0 = 0.1, f_alpha = 0.99, f_inc = 1.1, f_dec = 0.5;
  int n_delay = 5;
  void validate() const;
};

// The minimiser's own state between two iterations (with the System's velocities and the
// piston's velocity): enough to continue a stopped minimisation bit for bit.
struct FireState {
  double dt = 0.0;             // current time step
  double alpha = 0.0;          // current velocity mixing
  int n_positive = 0;          // iterations with P > 0 since the last reset
  std::uint64_t steps = 0;     // iterations done
  double wall_velocity = 0.0;  // the piston's velocity (0 without a pressure wall)
};

// Optional control of a minimisation: a stop request polled before every iteration, the
// state of a stopped minimisation to continue from, and the measured thread count to share
// between the minimisations of one protocol stage.
struct FireControl {
  std::function<bool()> stop;       // true: return before the next iteration, stopped
  std::optional<FireState> resume;  // continue from this state (velocities as left)
  // Each iteration runs on 1 thread or all, as measured to be faster (StepThreads; the
  // results do not depend on it). Null: the minimisation measures on its own. A compression
  // runs a short minimisation per step, so it keeps one measurement across them.
  StepThreads* threads = nullptr;
};

struct FireResult {
  bool converged = false;
  std::uint64_t steps = 0;
  double max_force = 0.0;
  double energy = 0.0;
  bool stopped = false;  // ended by control->stop; `state` continues it, velocities are kept
  FireState state;       // the state at the stop
};

class Fire {
 public:
  explicit Fire(const FireParams& params);
  const FireParams& params() const { return params_; }
  // Minimises; velocities are zeroed on return (unless stopped). `wall` may be null (walls
  // fixed). With `control`, a stop request ends the minimisation at the next iteration
  // boundary (result.stopped, result.state, no energy), and control->resume continues such a
  // minimisation: stopped + resumed equals one uninterrupted minimisation bit for bit.
  FireResult minimize(System& sys, ForceField& ff, PressureWall* wall = nullptr,
                      const FireControl* control = nullptr) const;

 private:
  FireParams params_;
};

}  // namespace invasim
