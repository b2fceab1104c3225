#include "abbe/diagnose/isotropic_scale.hpp"

#include <cmath>

#include "abbe/diagnose/statistics.hpp"

namespace abbe::diagnose {

IsotropicScale isotropic_scale(const std::vector<SelectedTerm>& effects, double alpha) {
  IsotropicScale r;
  std::vector<double> value, weight;
  auto usable = [](const Term& t, int axis) {
    return t.kind == TermKind::scale && t.axis == axis && !t.coef.empty() && !t.stderr_.empty() &&
           t.stderr_[0] > 0.0;
  };
  for (int axis = 0; axis < 3; ++axis) {
    const Term* scale = nullptr;
    bool from_smooth = false;
    for (const SelectedTerm& st : effects)
      if (usable(st.term, axis) && st.significant && st.ambiguous_with.empty()) {
        scale = &st.term;
        break;
      }
    // Without a named scale of the axis: the scale in a smooth function's
    // linear part, where its value exceeds its uncertainty (as a name's) and
    // the part is shown (kLinearPartMinShare).
    for (const SelectedTerm& st : effects)
      for (const Term& part : st.linear_parts)
        if (!scale && st.linear_share >= kLinearPartMinShare && usable(part, axis) &&
            std::abs(part.coef[0]) > part.stderr_[0]) {
          scale = &part;
          from_smooth = true;
        }
    if (!scale) continue;
    r.axes.push_back(axis);
    r.from_linear_part.push_back(from_smooth);
    value.push_back(scale->coef[0]);
    weight.push_back(1.0 / (scale->stderr_[0] * scale->stderr_[0]));
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
