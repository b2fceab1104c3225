#include "swap_test.hpp"

#include <algorithm>

#include "abbe/diagnose/statistics.hpp"

namespace abbe::diagnose::design {

SwapTest swap_test(const Problem& pb, const Mat& D, const std::vector<Mat>& cols, std::size_t e,
                   double alpha) {
  return swap_test(pb, D, cols, e, alpha, std::vector<bool>(cols.size(), true));
}

SwapTest swap_test(const Problem& pb, const Mat& D, const std::vector<Mat>& cols, std::size_t e,
                   double alpha, std::vector<bool> others) {
  SwapTest sw;
  others[e] = false;
  static_cast<span::SwapBasis&>(sw) = span::swap_basis(pb, D, cols, others, e);
  if (sw.rank == 0) return sw;
  const double dof = static_cast<double>(pb.y.size() - sw.QA.cols() - sw.rank);
  const double s2 = std::max(sw.rA.squaredNorm() - sw.d_e, 0.0) / std::max(dof, 1.0);
  sw.margin = s2 * chi2_upper_quantile(1, alpha);
  sw.valid = true;
  return sw;
}

void add_alternative(SelectedTerm& st, const std::string& alt) {
  if (std::find(st.ambiguous_with.begin(), st.ambiguous_with.end(), alt) == st.ambiguous_with.end())
    st.ambiguous_with.push_back(alt);
}

}  // namespace abbe::diagnose::design
