#include "setup/velocities.hpp"

#include <cmath>
#include <string>

#include "core/errors.hpp"
#include "core/rng.hpp"

namespace invasim {

void set_maxwell_boltzmann(System& sys, const std::vector<int>& sites, double kT) {
  if (!(kT >= 0.0) || !std::isfinite(kT))
    throw InputError("kT = " + std::to_string(kT) + " must be a finite number >= 0");
  Sites& s = sys.sites();
  for (int i : sites) {
    if (i < 0 || std::size_t(i) >= s.size())
      throw InputError("site " + std::to_string(i) + " is outside [0, " + std::to_string(s.size()) +
                       ")");
    const Vec3 g =
        RandomKey(sys.seed(), sys.step, std::uint32_t(i), RngStream::kVelocity).normal3();
    s.vel[i] = std::sqrt(kT / s.mass[i]) * g;
  }
}

}  // namespace invasim
