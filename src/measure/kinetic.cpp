#include "measure/kinetic.hpp"

namespace invasim {

double temperature(const System& sys, const std::vector<int>& sites) {
  const Sites& s = sys.sites();
  double sum = 0.0;
  for (int i : sites) sum += s.mass[i] * s.vel[i].squaredNorm();
  return sites.empty() ? 0.0 : sum / (3.0 * double(sites.size()));
}

}  // namespace invasim
