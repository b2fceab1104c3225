#include "linear_part.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

namespace abbe::diagnose::selection {

void fill_linear_part(const Problem& pb, const SmoothFitMap& fit, Eigen::Index col, const Vec& beta,
                      const Mat& Qd, SelectedTerm& st) {
  const Term& smooth = st.term;
  const int i = smooth.direction;
  const Eigen::Index k = beta.size();
  st.linear_parts.clear();
  st.linear_share = 0.0;
  if (smooth.kind != TermKind::unexplained || i < 0 || k == 0) return;
  // The parts d_i ∝ s_a, a each position variable of the function (t is not
  // a scale's variable), with their columns L̃ beside the datum (their datum
  // component removed, as the datum is fitted with every effect). A part the
  // datum holds whole (e.g. a squareness of a line measured in one
  // direction, which its rotation takes) is not a part of anything beyond
  // it: left out.
  std::vector<Term> parts;
  std::vector<Vec> columns;
  for (int a : smooth.vars) {
    if (a < 0 || a > 2) continue;
    const Term t = position_term(a, i);
    Vec c = term_columns(pb, t).col(0);
    const double before = c.squaredNorm();
    if (Qd.cols() > 0) c -= Qd * (Qd.transpose() * c);
    if (!(c.squaredNorm() > 1e-9 * before)) continue;
    parts.push_back(t);
    columns.push_back(std::move(c));
  }
  if (parts.empty()) return;
  const auto X = fit.smooth_X.middleCols(col, k);
  Mat L(X.rows(), static_cast<Eigen::Index>(parts.size()));
  for (std::size_t p = 0; p < parts.size(); ++p) L.col(static_cast<Eigen::Index>(p)) = columns[p];
  const Mat LtL = L.transpose() * L;
  const Eigen::LDLT<Mat> ldlt(LtL);
  // The parts of the function's values Xβ: c = W β, W = (L̃ᵀL̃)⁻¹ L̃ᵀ X.
  const Mat W = ldlt.solve(L.transpose() * X);
  const Vec c = W * beta;
  // c = G y with G = W (XᵀX)⁻¹_rows Xsᵀ (I − P_named), so for independent
  // noise Cov(c) = s² G Gᵀ = s² (G₀G₀ᵀ − (G₀Xn)(XnᵀXn)⁻¹(G₀Xn)ᵀ), G₀ = W (XᵀX)⁻¹_rows Xsᵀ
  // (I − P_named is a projection). Only m ≤ 3 rows are formed.
  const Mat G0 = (W * fit.smooth_inv.middleRows(col, k)) * fit.smooth_X.transpose();
  Mat cov = G0 * G0.transpose();
  if (fit.named_X.cols() > 0) {
    const Mat GX = G0 * fit.named_X;
    cov -= GX * fit.named_inv * GX.transpose();
  }
  cov *= fit.s2;
  for (std::size_t p = 0; p < parts.size(); ++p) {
    const auto pp = static_cast<Eigen::Index>(p);
    parts[p].coef = {c[pp]};
    parts[p].stderr_ = {std::sqrt(std::max(cov(pp, pp), 0.0))};
  }
  Vec f = X * beta;
  if (Qd.cols() > 0) f -= Qd * (Qd.transpose() * f);
  const double total = f.squaredNorm();
  st.linear_share = total > 0.0 ? std::min((L * c).squaredNorm() / total, 1.0) : 0.0;
  st.linear_parts = std::move(parts);
}

}  // namespace abbe::diagnose::selection
