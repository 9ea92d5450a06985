#pragma once
// FIRE energy minimiser (Bitzek et al. 2006, with the FIRE 2.0 refinements of Guenole et al.
// 2020: semi-implicit Euler, half-step back-off on uphill moves, delayed dt growth). All sites
// move; when a PressureWall is given the left wall is one more degree of freedom whose force
// is the site reaction plus P A, so the minimiser finds mechanical equilibrium at pressure P
// (its inertia there is m A / d^2, one layer of mean sites, or the wall's mass if larger).
// Converged when every site force is below ftol and the wall's net force per unit area is
// below ftol.
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

struct FireResult {
  bool converged = false;
  std::uint64_t steps = 0;
  double max_force = 0.0;
  double energy = 0.0;
};

class Fire {
 public:
  explicit Fire(const FireParams& params);
  const FireParams& params() const { return params_; }
  // Minimises; velocities are zeroed on return. `wall` may be null (walls fixed).
  FireResult minimize(System& sys, ForceField& ff, PressureWall* wall = nullptr) const;

 private:
  FireParams params_;
};

}  // namespace invasim
