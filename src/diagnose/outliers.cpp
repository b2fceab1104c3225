#include "abbe/diagnose/outliers.hpp"

#include <algorithm>
#include <cmath>

namespace abbe::diagnose {

double robust_sigma(const Eigen::VectorXd& r) {
  if (r.size() == 0) return 0.0;
  std::vector<double> a(static_cast<std::size_t>(r.size()));
  for (Eigen::Index i = 0; i < r.size(); ++i) a[static_cast<std::size_t>(i)] = std::abs(r[i]);
  const auto mid = a.begin() + static_cast<std::ptrdiff_t>(a.size() / 2);
  std::nth_element(a.begin(), mid, a.end());
  return 1.482602218505602 * *mid;
}

std::vector<std::uint32_t> points_beyond(const Problem& pb, const Eigen::VectorXd& r,
                                         double threshold) {
  std::vector<std::uint32_t> out;
  for (std::size_t o = 0; o < pb.obs.size(); ++o) {
    const double v = r[static_cast<Eigen::Index>(o)];
    if (!(std::abs(v) <= threshold)) out.push_back(pb.obs[o].point);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

Problem without_points(const Problem& pb, const std::vector<std::uint32_t>& drop) {
  if (drop.empty()) return pb;
  Problem out = pb;
  out.points.clear();
  out.lines.clear();
  out.obs.clear();
  std::vector<std::uint32_t> new_index(pb.points.size(), UINT32_MAX);
  std::size_t d = 0;
  for (std::size_t p = 0; p < pb.points.size(); ++p) {
    if (d < drop.size() && drop[d] == p) {
      ++d;
      continue;
    }
    new_index[p] = static_cast<std::uint32_t>(out.points.size());
    out.points.push_back(pb.points[p]);
    if (p < pb.lines.size()) out.lines.push_back(pb.lines[p]);
  }
  std::vector<double> y;
  y.reserve(pb.obs.size());
  for (std::size_t o = 0; o < pb.obs.size(); ++o) {
    const std::uint32_t p = new_index[pb.obs[o].point];
    if (p == UINT32_MAX) continue;
    out.obs.push_back({p, pb.obs[o].u});
    y.push_back(pb.y[static_cast<Eigen::Index>(o)]);
  }
  out.y = Eigen::Map<Eigen::VectorXd>(y.data(), static_cast<Eigen::Index>(y.size()));
  return out;
}

Eigen::VectorXd residual_after(const Problem& pb, const std::vector<SelectedTerm>& datum,
                               const std::vector<SelectedTerm>& effects) {
  Eigen::VectorXd r = pb.y;
  std::uint32_t last = UINT32_MAX;
  Eigen::Vector3d fit = Eigen::Vector3d::Zero();
  for (std::size_t o = 0; o < pb.obs.size(); ++o) {
    const Observation& ob = pb.obs[o];
    if (ob.point != last) {
      last = ob.point;
      fit.setZero();
      const PointContext& pc = pb.points[ob.point];
      for (const auto* list : {&datum, &effects})
        for (const SelectedTerm& st : *list) fit += st.term.evaluate(pc);
    }
    r[static_cast<Eigen::Index>(o)] -= ob.u.dot(fit);
  }
  return r;
}

}  // namespace abbe::diagnose
