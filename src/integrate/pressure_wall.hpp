#pragma once
// The left wall as a massive piston under a target pressure (docs/model.md, "Equations of
// motion"), integrated by Dynamics with the same modified velocity Verlet as the sites.
#include <memory>
#include <optional>

#include "forces/wall_force.hpp"
#include "integrate/ramp.hpp"

namespace invasim {

// M x'' = F_sites_on_wall + P A - gamma_w x' + xi, with xi the fluctuation-dissipation random
// force at temperature kT (variance 2 gamma_w kT / dt per step; kT = 0: no noise), drawn from
// the counter-based RNG (stream kPiston), so that it does not depend on the thread count and a
// restored run repeats it bit for bit.
//
// The step's arithmetic is in these member functions, compiled once in pressure_wall.cpp: GCC
// contracts a * b + c into a fused multiply-add (-ffp-contract=fast, its default for C++) or
// not depending on the surrounding code, so a copy of these lines elsewhere (a test's
// reference step) may round differently by 1 ulp. Every caller uses these.
struct PressureWall {
  double pressure = 0.0;
  double mass = 1.0;
  double gamma = 0.2;
  double kT = 0.0;  // temperature of the piston's bath
  double velocity = 0.0;
  double force = 0.0;  // total force on the wall at the last step
  std::shared_ptr<WallForce> walls;
  std::optional<Ramp> pressure_ramp;  // if set, `pressure` follows it step by step
  void validate() const;

  // velocity += dt/2 force / mass.
  void half_kick(double dt);
  // Moves the wall by dt velocity (Box::set_wall throws if the move is refused).
  void move(Box& box, double dt) const;
  // force = the sites' force on the wall (from `walls`' last evaluation) + P A - gamma v + xi,
  // with xi drawn for sys.step.
  void update_force(const System& sys, double dt);
};

}  // namespace invasim
