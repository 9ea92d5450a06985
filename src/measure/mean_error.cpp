#include "measure/mean_error.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/errors.hpp"

namespace invasim {

MeanError mean_error(std::span<const double> x) {
  MeanError r;
  r.n = x.size();
  if (x.empty()) return r;
  double sum = 0.0;
  for (double v : x) sum += v;
  r.mean = sum / double(x.size());
  if (x.size() < 2) return r;

  const std::size_t n = x.size();
  const double nd = double(n);
  std::vector<double> d(n);
  for (std::size_t i = 0; i < n; ++i) d[i] = x[i] - r.mean;
  // Autocovariance Gamma(t) = sum_i d_i d_(i+t) / n (divided by n, not n - t: the long lags'
  // noise stays down) up to the cap W_max = floor((kMaxWindowShare n - 1) / 2).
  const double cap = (kMaxWindowShare * nd - 1.0) / 2.0;
  const std::size_t w_max = std::min(n - 1, cap > 0.0 ? std::size_t(cap) : std::size_t(0));
  auto gamma = [&](std::size_t t) {
    double s = 0.0;
    for (std::size_t i = 0; i + t < n; ++i) s += d[i] * d[i + t];
    return s / nd;
  };
  const double gamma0 = gamma(0);
  if (!(gamma0 > 0.0)) {  // a constant series
    r.error = 0.0;
    r.tau_int = 0.5;
    r.resolved = true;
    return r;
  }
  double tau_w = 0.5;  // tau_int(W), W = 0
  std::size_t window = 0;
  for (std::size_t w = 1; w <= w_max; ++w) {
    tau_w += gamma(w) / gamma0;
    window = w;
    if (double(w) >= kSokalC * tau_w) {
      r.resolved = true;
      break;
    }
  }
  // C_F = 2 tau_int Var with the subtracted mean's bias corrected; the variance likewise
  // (Var = Gamma(0) + C_F / n). An anticorrelated series (tau_int < 1/2) is not credited:
  // it takes the independent samples' error, the usual std(ddof = 1) / sqrt(n).
  double c_f = 2.0 * tau_w * gamma0 / (1.0 - (2.0 * double(window) + 1.0) / nd);
  double variance = gamma0 + c_f / nd;
  if (c_f < variance) variance = c_f = gamma0 / (1.0 - 1.0 / nd);
  r.tau_int = c_f / (2.0 * variance);
  r.error = std::sqrt(c_f / nd);
  r.window = window;
  return r;
}

MeanError mean_error_tail(std::span<const double> x, double fraction) {
  if (!(fraction > 0.0 && fraction <= 1.0))
    fail_input("mean error: fraction = ", fraction, " must be in (0, 1]");
  const std::size_t keep = std::size_t(std::floor(fraction * double(x.size())));
  return mean_error(x.subspan(x.size() - keep));
}

}  // namespace invasim
