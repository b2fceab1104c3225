#include "abbe/diagnose/isotropic_scale.hpp"

#include <cmath>

#include "abbe/diagnose/statistics.hpp"

namespace abbe::diagnose {

IsotropicScale isotropic_scale(const std::vector<SelectedTerm>& effects, double alpha) {
  IsotropicScale r;
  std::vector<double> value, weight;
  for (int axis = 0; axis < 3; ++axis)
    for (const SelectedTerm& st : effects) {
      const Term& t = st.term;
      if (t.kind != TermKind::scale || t.axis != axis || !st.significant ||
          !st.ambiguous_with.empty())
        continue;
      if (t.coef.empty() || t.stderr_.empty() || !(t.stderr_[0] > 0.0)) continue;
      r.axes.push_back(axis);
      value.push_back(t.coef[0]);
      weight.push_back(1.0 / (t.stderr_[0] * t.stderr_[0]));
      break;
    }
  if (r.axes.size() < 2) return IsotropicScale{};
  double sw = 0.0, swv = 0.0;
  for (std::size_t i = 0; i < value.size(); ++i) {
    sw += weight[i];
    swv += weight[i] * value[i];
  }
  r.ppm = swv / sw;
  r.u_ppm = 1.0 / std::sqrt(sw);
  for (std::size_t i = 0; i < value.size(); ++i)
    r.chi2 += weight[i] * (value[i] - r.ppm) * (value[i] - r.ppm);
  r.found = r.chi2 <= chi2_upper_quantile(static_cast<int>(r.axes.size()) - 1, alpha);
  if (!r.found) return IsotropicScale{};
  return r;
}

}  // namespace abbe::diagnose
