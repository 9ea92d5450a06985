#include "setup/masses.hpp"

#include <cmath>
#include <string>

#include "core/errors.hpp"

namespace invasim {

void set_masses(System& sys, const std::vector<int>& sites, double mass) {
  if (!(mass > 0.0) || !std::isfinite(mass))
    throw InputError("mass = " + std::to_string(mass) + " must be finite and > 0");
  Sites& s = sys.sites();
  for (int i : sites)
    if (i < 0 || std::size_t(i) >= s.size())
      throw InputError("site " + std::to_string(i) + " is outside [0, " + std::to_string(s.size()) +
                       ")");
  for (int i : sites) s.mass[i] = mass;
}

}  // namespace invasim
