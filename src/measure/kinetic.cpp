#include "measure/kinetic.hpp"

#include <limits>

namespace invasim {

double temperature(const System& sys, const std::vector<int>& sites) {
  const Sites& s = sys.sites();
  double sum = 0.0;
  for (int i : sites) sum += s.mass[i] * s.vel[i].squaredNorm();
  if (sites.empty()) return std::numeric_limits<double>::quiet_NaN();  // undefined, not 0
  return sum / (3.0 * double(sites.size()));
}

}  // namespace invasim
