#include "final_fit.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "linear_part.hpp"
#include "searched_uncertainty.hpp"

namespace abbe::diagnose::selection {

void fit_chosen(const Problem& pb, const Mat& X, const Vec& y, const Mat& Qd, const Chosen& ch,
                SelectionResult& res) {
  const Eigen::Index n = y.size();
  const std::vector<Term>& chosen = ch.terms;
  const std::vector<Alternatives>& ambiguous = ch.ambiguous;
  const std::vector<std::string>& separations = ch.separations;
  const std::size_t n_datum = ch.n_datum;
  // Two stages: the named effects jointly, then the smooth (unexplained)
  // remainder on what they leave, so that the smooth functions cannot take
  // over part of a named effect's parameters.
  std::vector<Eigen::Index> start(chosen.size());
  {
    Eigen::Index col = 0;
    for (std::size_t i = 0; i < chosen.size(); ++i) {
      start[i] = col;
      col += chosen[i].columns();
    }
  }
  struct StageFit {
    std::vector<std::size_t> terms;
    Mat Xs;  // the stage's columns
    Vec beta;
    Mat inv;  // (XᵀX)⁻¹
  };
  auto fit_stage = [&](bool smooth, const Vec& target, Vec& residual) {
    StageFit f;
    Eigen::Index P = 0;
    for (std::size_t i = 0; i < chosen.size(); ++i)
      if ((chosen[i].kind == TermKind::unexplained) == smooth) {
        f.terms.push_back(i);
        P += chosen[i].columns();
      }
    residual = target;
    if (P == 0) return f;
    Mat& Xs = f.Xs;
    Xs.resize(n, P);
    Eigen::Index c = 0;
    for (std::size_t i : f.terms) {
      Xs.middleCols(c, chosen[i].columns()) = X.middleCols(start[i], chosen[i].columns());
      c += chosen[i].columns();
    }
    Mat XtX = Xs.transpose() * Xs;
    XtX.diagonal().array() += 1e-12 * XtX.trace() / static_cast<double>(P);
    Eigen::LDLT<Mat> ldlt(XtX);
    f.beta = ldlt.solve(Xs.transpose() * target);
    f.inv = ldlt.solve(Mat::Identity(P, P));
    residual = target - Xs * f.beta;
    return f;
  };
  Vec r1, r2;
  const StageFit named_fit = fit_stage(false, y, r1);
  const StageFit smooth_fit = fit_stage(true, r1, r2);
  res.residual = r2;
  const double s2 = r2.squaredNorm() / std::max<double>(static_cast<double>(n - X.cols()), 1.0);
  res.sigma_um = std::sqrt(s2);
  const Vec r_datum = y - Qd * (Qd.transpose() * y);
  // SS a term removes on its own from `target` (after the datum for the named stage).
  const Mat none(n, 0);
  auto alone = [&](std::size_t i, const Vec& target, bool smooth) {
    return removed_by(X.middleCols(start[i], chosen[i].columns()), smooth ? none : Qd, target);
  };
  for (const StageFit* f : {&named_fit, &smooth_fit}) {
    const bool smooth = f == &smooth_fit;
    Eigen::Index col = 0;
    std::vector<SelectedTerm> stage;
    std::vector<double> overlap;
    double unique_sum = 0.0;
    for (std::size_t i : f->terms) {
      SelectedTerm st;
      st.term = chosen[i];
      const auto k = static_cast<Eigen::Index>(st.term.columns());
      const Vec bt = f->beta.segment(col, k);
      const Mat Vt = f->inv.block(col, col, k, k);
      for (Eigen::Index c = 0; c < k; ++c) {
        st.term.coef.push_back(bt[c]);
        st.term.stderr_.push_back(std::sqrt(std::max(s2 * Vt(c, c), 0.0)));
      }
      if (!smooth && i >= n_datum)
        st.term.searched_stderr = searched_parameter_stderr(pb, st.term, f->Xs, f->inv, s2);
      if (smooth)
        fill_linear_part(pb, {named_fit.Xs, named_fit.inv, f->Xs, f->inv, s2}, col, bt, Qd, st);
      // SS this term alone removes given the others of its stage: βᵀ V⁻¹ β.
      const double drop = bt.dot(Vt.ldlt().solve(bt));
      const double of = i < n_datum ? res.baseline_sse : res.datum_sse;
      st.explained_fraction = of > 0.0 ? drop / of : 0.0;
      st.unique_fraction = st.explained_fraction;
      st.ambiguous_with = ambiguous[i].names;
      st.other_periods_mm = ambiguous[i].periods_mm;
      if (!ambiguous[i].empty()) st.separate_by = separations[i];
      col += k;
      if (i < n_datum) {
        res.datum.push_back(std::move(st));
        continue;
      }
      unique_sum += drop;
      overlap.push_back(std::max(alone(i, smooth ? r1 : r_datum, smooth) - drop, 0.0));
      stage.push_back(std::move(st));
    }
    // What the stage's effects remove together; the part no single one
    // removes alone is shared in proportion to the overlaps.
    const double together =
        smooth ? r1.squaredNorm() - r2.squaredNorm() : r_datum.squaredNorm() - r1.squaredNorm();
    const double shared = together - unique_sum;
    double overlap_sum = 0.0;
    for (double v : overlap) overlap_sum += v;
    for (std::size_t j = 0; j < stage.size(); ++j) {
      const double part = overlap_sum > 0.0 ? shared * overlap[j] / overlap_sum
                                            : shared / static_cast<double>(stage.size());
      stage[j].shared_fraction = res.datum_sse > 0.0 ? part / res.datum_sse : 0.0;
      stage[j].explained_fraction = stage[j].unique_fraction + stage[j].shared_fraction;
      res.explained_together += stage[j].explained_fraction;
      res.terms.push_back(std::move(stage[j]));
    }
  }
  std::stable_sort(res.terms.begin(), res.terms.end(),
                   [](const SelectedTerm& a, const SelectedTerm& b) {
                     return a.explained_fraction > b.explained_fraction;
                   });
}

}  // namespace abbe::diagnose::selection
