#include "measure/packing.hpp"

#include <cmath>

#include "core/errors.hpp"

namespace invasim {

PackingFractions packing_fractions(const System& sys) {
  double cells = 0.0;
  const Sites& s = sys.sites();
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.kind[i] == SiteKind::kCancer) cells += M_PI / 6.0 * std::pow(s.diameter[i], 3);
  double bodies = 0.0;
  for (std::size_t b = 0; b < sys.bodies().size(); ++b) {
    const double v = sys.bodies()[b].outer_volume;
    if (!(v > 0.0)) fail_input("packing fraction: adipocyte ", b, " has no outer volume (V_i) set");
    bodies += v;
  }
  const double volume = sys.box().volume();
  return {(cells + bodies) / volume, cells / volume, bodies / volume};
}

}  // namespace invasim
