#include "measure/kinetic.hpp"

#include <limits>

namespace invasim {

double temperature(const System& sys, const std::vector<int>& sites) {
  if (sites.empty()) return std::numeric_limits<double>::quiet_NaN();  // undefined, not 0
  const Sites& s = sys.sites();
  double sum = 0.0;
  for (int i : sites) sum += s.mass[i] * s.vel[i].squaredNorm();
  return sum / (3.0 * double(sites.size()));
}

}  // namespace invasim
