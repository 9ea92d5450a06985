#include "forces/wall_force.hpp"
#include "core/parallel.hpp"

#include "core/deterministic_sum.hpp"
#include "core/errors.hpp"

namespace invasim {

WallForce::WallForce(double eps, bool left, bool right) : eps_(eps), left_(left), right_(right) {
  require_positive("wall eps", eps);
}

void WallForce::prepare_team(System& sys, const ForceFlags&) {
  if (sys.box().periodic(0))
    fail_input("walls: the box is periodic in x; walls need a walled x axis");
  partial_.resize(sum_blocks(sys.n_sites()));
}

ForceResult WallForce::add_forces_team(System& sys, const ForceFlags& flags) {
  Sites& s = sys.sites();
  const std::size_t n = s.size();
  const double xl = sys.box().lo()[0], xr = sys.box().hi()[0];
  // Each site's push and its share of the wall forces, energy and virial, summed in fixed blocks.
  const PerSite total = team_deterministic_sum(n, PerSite{}, partial_, [&](std::size_t i) {
    PerSite p;
    const double x = s.pos[i][0], sig = s.diameter[i];
    if (left_ && x - xl <= sig) {
      const double u = 1.0 - (x - xl) / sig;
      const double f = eps_ / sig * u;  // pushes the site toward +x
      s.force[i][0] += f;
      p.left = -f;
      p.energy += 0.5 * eps_ * u * u;
      p.virial += (x - xl) * f;
    }
    if (right_ && xr - x <= sig) {
      const double u = 1.0 - (xr - x) / sig;
      const double f = -eps_ / sig * u;
      s.force[i][0] += f;
      p.right = -f;
      p.energy += 0.5 * eps_ * u * u;
      p.virial += (x - xr) * f;
    }
    return p;
  });
  if (team_leader()) {
    left_force_ = total.left;
    right_force_ = total.right;
  }
  ForceResult out;
  if (flags.energy) out.energy = total.energy;
  if (flags.virial) out.virial = Vec3(total.virial, 0.0, 0.0);
  return out;
}

}  // namespace invasim
