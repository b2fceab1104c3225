#include "final_refit.hpp"

#include "span.hpp"

namespace abbe::diagnose::selection {

namespace {

// X split into its terms' blocks, where X holds the terms' columns side by
// side in order: each block and its first column. False when X's columns
// are not those.
bool split_by_terms(const Eigen::MatrixXd& X, const std::vector<Term>& terms,
                    std::vector<Eigen::MatrixXd>& blocks, std::vector<Eigen::Index>& start) {
  blocks.clear();
  start.clear();
  Eigen::Index columns = 0;
  for (const Term& t : terms) {
    if (columns + t.columns() > X.cols()) return false;
    start.push_back(columns);
    blocks.emplace_back(X.middleCols(columns, t.columns()));
    columns += t.columns();
  }
  return columns == X.cols();
}

}  // namespace

bool refine_each_beside_others(const Problem& pb, Mat& X, const Vec& y, std::vector<Term>& chosen,
                               const FinalRefit& how, std::vector<std::string>& log) {
  std::vector<Mat> blocks;
  std::vector<Eigen::Index> start;
  if (!split_by_terms(X, chosen, blocks, start)) return false;
  const Mat none(X.rows(), 0);
  bool moved = false;
  for (std::size_t i = 0; i < chosen.size(); ++i) {
    if (!how.applies(chosen[i])) continue;
    // Everything else of the named stage, and the data beside it.
    std::vector<bool> others(chosen.size());
    for (std::size_t j = 0; j < chosen.size(); ++j)
      others[j] = j != i && chosen[j].kind != TermKind::unexplained;
    const Mat Q = span::basis_of(none, blocks, others);
    const Vec r = span::residual_of(Q, y);
    const Mat& C = blocks[i];
    const double before = delta_rss(C, C.transpose() * C, Q.transpose() * C, r);
    auto [refined, after] = how.refine(chosen[i], Q, r);
    if (!(after > before)) continue;
    log.push_back(how.describe(chosen[i], refined, before, after));
    chosen[i] = std::move(refined);
    blocks[i] = term_columns(pb, chosen[i]);
    X.middleCols(start[i], chosen[i].columns()) = blocks[i];
    moved = true;
  }
  return moved;
}

}  // namespace abbe::diagnose::selection
