#include "measure/mean_error.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/errors.hpp"

namespace invasim {

IntegratedTime integrated_time(std::span<const double> r, std::size_t fitted) {
  IntegratedTime t;
  const std::size_t n = r.size();
  if (fitted == 0 || n <= std::max<std::size_t>(1, fitted)) return t;
  const double nd = double(n), p = double(fitted);
  // Autocovariance Gamma(s) = sum_i r_i r_(i+s) / n (divided by n, not n - s: the long lags'
  // noise stays down) up to the cap W_max = floor((kMaxWindowShare n / fitted - 1) / 2).
  const double cap = (kMaxWindowShare * nd / p - 1.0) / 2.0;
  const std::size_t w_max = std::min(n - 1, cap > 0.0 ? std::size_t(cap) : std::size_t(0));
  auto gamma = [&](std::size_t s) {
    double sum = 0.0;
    for (std::size_t i = 0; i + s < n; ++i) sum += r[i] * r[i + s];
    return sum / nd;
  };
  const double gamma0 = gamma(0);
  if (!(gamma0 > 0.0)) {  // no fluctuation
    t.tau_int = 0.5;
    t.removed = 0.0;
    t.resolved = true;
    return t;
  }
  double tau_w = 0.5;  // tau_int(W), W = 0
  for (std::size_t w = 1; w <= w_max; ++w) {
    tau_w += gamma(w) / gamma0;
    t.window = w;
    if (double(w) >= kSokalC * tau_w) {
      t.resolved = true;
      break;
    }
  }
  // C_F = 2 tau_int Var with the fit's bias corrected; the variance likewise (Var = Gamma(0)
  // + fitted C_F / n). Anticorrelated fluctuations (tau_int < 1/2) are not credited: they
  // take the independent samples' variance, Gamma(0) n / (n - fitted).
  double c_f = 2.0 * tau_w * gamma0 / (1.0 - p * (2.0 * double(t.window) + 1.0) / nd);
  double variance = gamma0 + p * c_f / nd;
  if (c_f < variance) variance = c_f = gamma0 / (1.0 - p / nd);
  t.tau_int = c_f / (2.0 * variance);
  t.removed = variance - gamma0;
  return t;
}

double error_of_mean(std::span<const double> r, const IntegratedTime& t) {
  double squares = 0.0;
  for (double v : r) squares += v * v;
  const double n = double(r.size());
  return std::sqrt((squares / n + t.removed) * 2.0 * t.tau_int / n);
}

MeanError mean_error(std::span<const double> x) {
  MeanError m;
  m.n = x.size();
  if (x.empty()) return m;
  double sum = 0.0;
  for (double v : x) sum += v;
  m.mean = sum / double(x.size());
  if (x.size() < 2) return m;
  std::vector<double> d(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) d[i] = x[i] - m.mean;
  const IntegratedTime t = integrated_time(d, 1);
  m.error = error_of_mean(d, t);
  m.tau_int = t.tau_int;
  m.window = t.window;
  m.resolved = t.resolved;
  return m;
}

MeanError mean_error_tail(std::span<const double> x, double fraction) {
  if (!(fraction > 0.0 && fraction <= 1.0))
    fail_input("mean error: fraction = ", fraction, " must be in (0, 1]");
  const std::size_t keep = std::size_t(std::floor(fraction * double(x.size())));
  return mean_error(x.subspan(x.size() - keep));
}

}  // namespace invasim
