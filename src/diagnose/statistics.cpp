#include "abbe/diagnose/statistics.hpp"

#include <cmath>

namespace abbe::diagnose {

double normal_upper_quantile(double alpha) {
  // Bisection on P(Z > z) = erfc(z/√2)/2, monotone decreasing in z.
  double lo = -40.0, hi = 40.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (0.5 * std::erfc(mid / std::sqrt(2.0)) > alpha)
      lo = mid;
    else
      hi = mid;
  }
  return 0.5 * (lo + hi);
}

double chi2_upper_quantile(int k, double alpha) {
  const double z = normal_upper_quantile(alpha);
  const double kk = static_cast<double>(k);
  const double a = 2.0 / (9.0 * kk);
  const double c = 1.0 - a + z * std::sqrt(a);
  return kk * c * c * c;
}

}  // namespace abbe::diagnose
