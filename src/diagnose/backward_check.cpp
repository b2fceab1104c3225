#include "backward_check.hpp"

#include <Eigen/Cholesky>
#include <algorithm>

#include "abbe/diagnose/statistics.hpp"

namespace abbe::diagnose::selection {

std::optional<Redundant> least_needed_named(const Mat& X, const Mat& Qd, const Vec& y,
                                            const std::vector<Term>& chosen, std::size_t n_datum,
                                            double s2, double alpha) {
  // The named effects' column blocks in X.
  struct Block {
    std::size_t index;
    Eigen::Index first, count;
  };
  std::vector<Block> blocks;
  Eigen::Index at = 0, named_columns = 0;
  for (std::size_t i = 0; i < chosen.size(); ++i) {
    const Eigen::Index k = chosen[i].columns();
    if (i >= n_datum && chosen[i].kind != TermKind::unexplained) {
      blocks.push_back({i, at, k});
      named_columns += k;
    }
    at += k;
  }
  if (at != X.cols() || blocks.empty() || !(s2 > 0.0)) return std::nullopt;

  // The named columns and the data beside the datum.
  Mat C(X.rows(), named_columns);
  Eigen::Index c0 = 0;
  for (const Block& b : blocks) {
    C.middleCols(c0, b.count) = X.middleCols(b.first, b.count);
    c0 += b.count;
  }
  Vec yd = y;
  if (Qd.cols() > 0) {
    C -= Qd * (Qd.transpose() * C);
    yd -= Qd * (Qd.transpose() * y);
  }
  // Normal equations, columns scaled to unit norm (a tiny ridge for
  // near-dependent columns). Dropping block J of the least-squares fit
  // raises the RSS by β_Jᵀ [(G⁻¹)_JJ]⁻¹ β_J (the Wald form; invariant
  // under the column scaling).
  Mat G = C.transpose() * C;
  Vec scale(named_columns);
  for (Eigen::Index c = 0; c < named_columns; ++c)
    scale[c] = G(c, c) > 0.0 ? 1.0 / std::sqrt(G(c, c)) : 0.0;
  G = scale.asDiagonal() * G * scale.asDiagonal();
  G.diagonal().array() += 1e-10;
  const Vec b = scale.asDiagonal() * (C.transpose() * yd);
  const Eigen::LDLT<Mat> ldlt(G);
  const Mat Ginv = ldlt.solve(Mat::Identity(named_columns, named_columns));
  const Vec beta = Ginv * b;

  std::optional<Redundant> weakest;
  double weakest_ratio = 1.0;
  c0 = 0;
  for (const Block& blk : blocks) {
    const Vec bj = beta.segment(c0, blk.count);
    const Mat Vj = Ginv.block(c0, c0, blk.count, blk.count);
    c0 += blk.count;
    const double d = std::max(bj.dot(Vj.ldlt().solve(bj)), 0.0);
    const double thr = s2 * chi2_upper_quantile(static_cast<int>(blk.count), alpha);
    if (d / thr < weakest_ratio) {
      weakest_ratio = d / thr;
      weakest = Redundant{blk.index, blk.first, d, thr};
    }
  }
  return weakest;
}

}  // namespace abbe::diagnose::selection
