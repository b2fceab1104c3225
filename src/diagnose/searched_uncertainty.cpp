#include "searched_uncertainty.hpp"

#include <cmath>
#include <limits>

#include "abbe/diagnose/selection.hpp"

namespace abbe::diagnose::selection {

Vec searched_derivative(const Problem& pb, const Term& fitted) {
  double Term::*param = nullptr;
  if (fitted.kind == TermKind::cyclic && fitted.period_mm > 0.0) param = &Term::period_mm;
  if (fitted.kind == TermKind::thermal_drift && fitted.tau_s > 0.0) param = &Term::tau_s;
  if (!param || fitted.coef.empty()) return Vec();
  const Vec beta =
      Eigen::Map<const Vec>(fitted.coef.data(), static_cast<Eigen::Index>(fitted.coef.size()));
  const double theta = fitted.*param;
  const double h = 1e-5 * theta;
  Term up = fitted, down = fitted;
  up.*param = theta + h;
  down.*param = theta - h;
  return (term_columns(pb, up) * beta - term_columns(pb, down) * beta) / (2.0 * h);
}

double searched_parameter_stderr(const Problem& pb, const Term& fitted, const Mat& X,
                                 const Mat& XtX_inv, double s2) {
  const Vec d = searched_derivative(pb, fitted);
  if (d.size() == 0) return 0.0;
  Vec d_perp = d;
  if (X.cols() > 0) d_perp -= X * (XtX_inv * (X.transpose() * d));
  const double left = d_perp.squaredNorm();
  // Less than rounding of what the derivative holds: nothing fixes θ.
  if (!(left > 1e-12 * d.squaredNorm())) return std::numeric_limits<double>::infinity();
  return std::sqrt(s2 / left);
}

}  // namespace abbe::diagnose::selection
