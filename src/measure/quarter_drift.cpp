#include "measure/quarter_drift.hpp"

#include <cmath>
#include <vector>

#include "measure/mean_error.hpp"

namespace invasim {

QuarterDrift quarter_drift(std::span<const double> window) {
  QuarterDrift d;
  const std::size_t q = window.size() / 2;
  d.quarter = q;
  if (q < 2) return d;
  const std::span<const double> y = window.subspan(window.size() - 2 * q);
  // Least squares of y on (quarter 3's indicator, quarter 4's, x), x = i - (q - 1)/2 within
  // each quarter: the columns are orthogonal, so the quarters' means are their plain means
  // and the common slope is sum x (y - m) / sum x^2 over both.
  double m[2] = {0.0, 0.0};
  for (std::size_t i = 0; i < 2 * q; ++i) m[i / q] += y[i];
  m[0] /= double(q);
  m[1] /= double(q);
  auto x = [q](std::size_t i) { return double(i % q) - 0.5 * double(q - 1); };
  double xy = 0.0, xx = 0.0;
  for (std::size_t i = 0; i < 2 * q; ++i) {
    xy += x(i) * (y[i] - m[i / q]);
    xx += x(i) * x(i);
  }
  const double slope = xx > 0.0 ? xy / xx : 0.0;
  std::vector<double> r(2 * q);
  for (std::size_t i = 0; i < 2 * q; ++i) r[i] = y[i] - m[i / q] - slope * x(i);
  const IntegratedTime t = integrated_time(r, 3);
  const std::span<const double> rs(r);
  const double e3 = error_of_mean(rs.first(q), t), e4 = error_of_mean(rs.last(q), t);
  d.m3 = m[0];
  d.m4 = m[1];
  d.drift = m[1] - m[0];
  d.error = std::hypot(e3, e4);
  d.tau_int = t.tau_int;
  d.resolved = t.resolved;
  return d;
}

}  // namespace invasim
