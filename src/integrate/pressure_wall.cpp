#include "integrate/pressure_wall.hpp"

#include <cmath>

#include "core/errors.hpp"
#include "core/rng.hpp"

namespace invasim {

void PressureWall::validate() const {
  require_non_negative("pressure", pressure);
  require_positive("wall mass", mass);
  require_non_negative("wall gamma", gamma);
  require_non_negative("wall kT", kT);
  if (!walls) fail_input("pressure wall: no wall force to couple to");
}

void PressureWall::half_kick(double dt) {
  velocity += 0.5 * dt / mass * force;
}

void PressureWall::move(Box& box, double dt) const {
  box.set_wall(0, false, box.lo()[0] + dt * velocity);
}

void PressureWall::update_force(const System& sys, double dt) {
  force = walls->left_wall_force() + pressure * sys.box().wall_area() - gamma * velocity;
  if (kT > 0.0) {
    const double noise = std::sqrt(2.0 * gamma * kT / dt);
    force += noise * RandomKey(sys.seed(), sys.step, 0u, RngStream::kPiston).normal3()[0];
  }
}

}  // namespace invasim
