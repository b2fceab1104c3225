#include "abbe/diagnose/selection.hpp"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "backward_check.hpp"
#include "candidate_fit.hpp"
#include "choose_step.hpp"
#include "chosen_periods.hpp"
#include "final_fit.hpp"
#include "path.hpp"
#include "span.hpp"
#include "time_constant.hpp"

namespace abbe::diagnose {
using selection::fit_chosen;
using selection::Mat;
using selection::motion_squared;
using selection::Vec;
using span::append_orthonormal;

std::vector<int> point_folds(std::size_t points, int folds, std::uint64_t seed) {
  std::vector<std::size_t> order(points);
  std::iota(order.begin(), order.end(), 0);
  std::mt19937_64 rng(seed);
  std::shuffle(order.begin(), order.end(), rng);
  std::vector<int> fold(points, 0);
  for (std::size_t i = 0; i < points; ++i)
    fold[order[i]] = static_cast<int>(i % static_cast<std::size_t>(std::max(folds, 1)));
  return fold;
}

Eigen::MatrixXd term_columns(const Problem& pb, const Term& term) {
  const int k = term.columns();
  Mat C(static_cast<Eigen::Index>(pb.obs.size()), k);
  Eigen::Matrix<double, 3, Eigen::Dynamic> g(3, k);
  std::uint32_t last = UINT32_MAX;
  for (std::size_t o = 0; o < pb.obs.size(); ++o) {
    const Observation& ob = pb.obs[o];
    if (ob.point != last) {
      term.basis(pb.points[ob.point], g);
      last = ob.point;
    }
    const double u0 = ob.u[0], u1 = ob.u[1], u2 = ob.u[2];
    const double* gd = g.data();
    for (int c = 0; c < k; ++c, gd += 3)
      C(static_cast<Eigen::Index>(o), c) = u0 * gd[0] + u1 * gd[1] + u2 * gd[2];
  }
  return C;
}

double cross_validated_sse(const Problem& pb, const Eigen::MatrixXd& X, const Eigen::VectorXd& y,
                           const std::vector<int>& fold_of_point, int folds) {
  const Eigen::Index P = X.cols();
  if (P == 0) return y.squaredNorm();
  std::vector<std::vector<Eigen::Index>> rows(static_cast<std::size_t>(folds));
  for (std::size_t o = 0; o < pb.obs.size(); ++o)
    rows[static_cast<std::size_t>(fold_of_point[pb.obs[o].point])].push_back(
        static_cast<Eigen::Index>(o));
  std::vector<Mat> G(rows.size());
  std::vector<Vec> b(rows.size());
  std::vector<double> yy(rows.size());
  Mat Gt = Mat::Zero(P, P);
  Vec bt = Vec::Zero(P);
  for (std::size_t f = 0; f < rows.size(); ++f) {
    const Mat Xf = X(rows[f], Eigen::all);
    const Vec yf = y(rows[f]);
    G[f] = Xf.transpose() * Xf;
    b[f] = Xf.transpose() * yf;
    yy[f] = yf.squaredNorm();
    Gt += G[f];
    bt += b[f];
  }
  const double ridge = 1e-10 * Gt.trace() / static_cast<double>(P);
  double sse = 0.0;
  for (std::size_t f = 0; f < rows.size(); ++f) {
    if (rows[f].empty()) continue;
    Mat A = Gt - G[f];
    A.diagonal().array() += ridge;
    const Vec beta = A.ldlt().solve(bt - b[f]);
    sse += yy[f] - 2.0 * beta.dot(b[f]) + beta.dot(G[f] * beta);
  }
  return sse;
}

namespace {

// A smooth function's flexibility: the Legendre degree with the least
// held-out SSE among the options' degrees (its columns at most half the
// observations). True when another degree than the candidates' fixed one
// was taken: pick, C (its columns), Xn (X with them) and cv updated.
bool choose_smooth_degree(const Problem& pb, const SelectionOptions& o, const Mat& X, const Vec& y,
                          const std::vector<int>& folds, Term& pick, Mat& C, Mat& Xn, double& cv) {
  const auto n = static_cast<Eigen::Index>(pb.obs.size());
  const int fixed_degree = pick.degree;
  for (int degree : pick.vars.size() == 1 ? o.single_degrees : o.pair_degrees) {
    if (degree == fixed_degree) continue;
    Term t = pick;
    t.degree = degree;
    const Mat Ct = term_columns(pb, t);
    if (static_cast<double>(X.cols() + Ct.cols()) > 0.5 * static_cast<double>(n)) continue;
    Mat Xt(n, X.cols() + Ct.cols());
    Xt << X, Ct;
    const double cvt = cross_validated_sse(pb, Xt, y, folds, o.folds);
    if (cvt < cv) {
      cv = cvt;
      pick = t;
      C = Ct;
      Xn = std::move(Xt);
    }
  }
  return pick.degree != fixed_degree;
}

}  // namespace

bool names(const std::vector<SelectedTerm>& effects, const Term& term) {
  const std::string label = term.label();
  return std::any_of(effects.begin(), effects.end(),
                     [&](const SelectedTerm& st) { return st.term.label() == label; });
}

SelectionResult selection::select_path(const Problem& pb, const CandidateSet& cs,
                                       const SelectionOptions& o, const Term* forced_first,
                                       selection::PathSummary& summary) {
  SelectionResult res;
  summary = {};
  const auto n = static_cast<Eigen::Index>(pb.obs.size());
  const auto np = pb.points.size();
  const Vec& y = pb.y;
  res.baseline_sse = y.squaredNorm();
  const std::vector<int> folds = point_folds(np, o.folds, o.seed);

  // The datum: always in the fit, before any effect.
  Mat Q(n, 0);
  Mat X(n, 0);
  std::vector<Term> chosen;
  std::vector<Alternatives> ambiguous;
  std::vector<std::string> separations;  // per chosen term: what would tell it from its rivals
  std::vector<int> step_of;              // per chosen term: its step (−1: the datum)
  for (const Term& t : cs.datum) {
    const Mat C = term_columns(pb, t);
    // Invisible in these data beyond the datum so far: the measured
    // directions see (almost) none of what the term moves, or only what
    // the offsets already take — e.g. the rotation of a circle measured
    // along its radius, whose part that the file's rounding leaves is
    // tangential, and whose centroid lies off the centre on a partial arc
    // or a closed one that repeats its first reading (that shift is a
    // constant offset). A column kept at the rounding's level would make
    // the datum's fit ill-conditioned and its offsets meaningless.
    if (!(span::residual_of(Q, C).squaredNorm() > 1e-6 * motion_squared(pb, t))) continue;
    const Eigen::Index before = Q.cols();
    append_orthonormal(Q, C);
    if (Q.cols() == before) continue;  // already in the span of the datum
    Mat Xn(n, X.cols() + C.cols());
    Xn << X, C;
    X = std::move(Xn);
    chosen.push_back(t);
    ambiguous.emplace_back();
    separations.emplace_back();
    step_of.push_back(-1);
  }
  const std::size_t n_datum = chosen.size();
  const Mat Qd = Q;  // the datum's span
  Vec r = y - Q * (Q.transpose() * y);
  res.datum_sse = r.squaredNorm();
  double cv_prev = X.cols() > 0 ? cross_validated_sse(pb, X, y, folds, o.folds) : res.baseline_sse;
  res.datum_cv_sse = cv_prev;

  // Named candidates without a searched parameter: columns cached once.
  selection::PathState ps(pb, cs, o, Q);
  for (int step = 0; step < o.max_terms; ++step) {
    if (o.on_step) o.on_step(step);
    const double rr = r.squaredNorm();
    const double dof_base = static_cast<double>(n - Q.cols());
    if (dof_base < 4.0) break;
    selection::StepChoice ch;
    if (forced_first && step == 0) {
      ch.pick = *forced_first;
      ch.C = term_columns(pb, ch.pick);
      ch.d = selection::removed_by(ch.C, Q, r);
    } else if (!selection::choose_step(pb, cs, o, ps, Q, r, step, ch, res.log,
                                       step == 0 ? &summary : nullptr)) {
      break;
    }
    Term& pick = ch.pick;
    Mat& C = ch.C;
    double& d_pick = ch.d;

    // Held-out check. A smooth function that fails it gives way to the best
    // significant named candidate (with fewer columns it may still pass).
    Mat Xn(n, X.cols() + C.cols());
    Xn << X, C;
    double cv = cross_validated_sse(pb, Xn, y, folds, o.folds);
    if (pick.kind == TermKind::unexplained) {
      const int fixed_degree = pick.degree;
      if (choose_smooth_degree(pb, o, X, y, folds, pick, C, Xn, cv)) {
        d_pick = selection::removed_by(C, Q, r);
        res.log.push_back(fmt::format("step {}: {} degree {} (held-out SSE; candidates' {})",
                                      step + 1, pick.label(), pick.degree, fixed_degree));
      }
    }
    if (!(cv < cv_prev * (1.0 - 1e-6)) && pick.kind == TermKind::unexplained && ch.fallback) {
      res.log.push_back(fmt::format("step {}: {} rejected: held-out SSE {:.6g} ≥ {:.6g}", step + 1,
                                    pick.label(), cv, cv_prev));
      pick = *ch.fallback;
      C = std::move(ch.fallback_C);
      d_pick = ch.fallback_d;
      ch.amb.clear();
      ch.separation.clear();
      Xn.resize(n, X.cols() + C.cols());
      Xn << X, C;
      cv = cross_validated_sse(pb, Xn, y, folds, o.folds);
    }
    if (!(cv < cv_prev * (1.0 - 1e-6))) {
      res.log.push_back(fmt::format("step {}: {} rejected: held-out SSE {:.6g} ≥ {:.6g}", step + 1,
                                    pick.label(), cv, cv_prev));
      break;
    }
    std::string picked = pick.label();
    for (const Term& t : ch.partners) picked += " + " + t.label();
    res.log.push_back(fmt::format("step {}: {} ΔRSS {:.6g} (of {:.6g}), held-out SSE {:.6g}",
                                  step + 1, picked, d_pick, rr, cv));
    cv_prev = cv;
    X = std::move(Xn);
    const Eigen::Index p0 = Q.cols();
    append_orthonormal(Q, C);
    const Mat Qnew = Q.rightCols(Q.cols() - p0);
    r -= Qnew * (Qnew.transpose() * r);
    chosen.push_back(pick);
    ambiguous.push_back(ch.amb);
    separations.push_back(ch.separation);
    step_of.push_back(step);
    if (step == 0 && ch.partners.empty() && pick.kind != TermKind::unexplained)
      summary.first = pick;
    for (std::size_t i = 0; i < ch.partners.size(); ++i) {
      chosen.push_back(ch.partners[i]);
      ambiguous.push_back(ch.partner_amb[i]);
      separations.push_back(ch.partner_separation[i]);
      step_of.push_back(step);
    }
    // This step's picks: the pick and its partners, the last of `chosen`.
    ps.advance(Qnew,
               std::vector<Term>(chosen.end() - 1 - static_cast<std::ptrdiff_t>(ch.partners.size()),
                                 chosen.end()));
  }

  // The backward check (backward_check.hpp): a named effect that the ones
  // chosen after it made redundant leaves the fit, the weakest first.
  auto backward_check = [&] {
    while (o.backward_check && chosen.size() > n_datum) {
      const double dof = static_cast<double>(n - Q.cols());
      if (dof < 1.0) break;
      const auto weak = selection::least_needed_named(
          X, Qd, y, chosen, n_datum, r.squaredNorm() / dof, o.alpha / ps.tests_named);
      if (!weak) break;
      res.log.push_back(fmt::format(
          "backward check: {} dropped: ΔRSS {:.6g} beside the other effects, below {:.6g}",
          chosen[weak->index].label(), weak->delta_rss, weak->threshold));
      const Eigen::Index first = weak->first_column;
      const Eigen::Index k = chosen[weak->index].columns();
      Mat Xn(n, X.cols() - k);
      Xn << X.leftCols(first), X.rightCols(X.cols() - first - k);
      X = std::move(Xn);
      const auto at = static_cast<std::ptrdiff_t>(weak->index);
      // The rivals found for its partners in the same step were rivals beside
      // it: the final rival check (rival_check.hpp) judges them anew.
      for (std::size_t i = 0; i < chosen.size(); ++i)
        if (step_of[i] == step_of[weak->index]) {
          ambiguous[i].clear();
          separations[i].clear();
        }
      chosen.erase(chosen.begin() + at);
      ambiguous.erase(ambiguous.begin() + at);
      separations.erase(separations.begin() + at);
      step_of.erase(step_of.begin() + at);
      Q = span::orthonormal(X);
      r = y - Q * (Q.transpose() * y);
      cv_prev = cross_validated_sse(pb, X, y, folds, o.folds);
    }
  };
  backward_check();

  // Final joint fit of every chosen term.
  res.cv_sse = cv_prev;
  res.residual = r;
  summary.rss = r.squaredNorm();
  if (chosen.size() == n_datum) {
    res.sigma_um =
        std::sqrt(r.squaredNorm() / std::max<double>(static_cast<double>(n - X.cols()), 1.0));
    if (chosen.empty()) return res;
  }
  if (o.refine_tau || o.refine_periods) {
    bool moved = o.refine_tau && selection::refine_time_constants(pb, X, y, chosen, res.log);
    if (o.refine_periods)
      moved = selection::refine_chosen_periods(pb, cs, X, y, chosen, res.log) || moved;
    // A drift at its own τ may make an effect chosen beside it at the
    // grid's τ redundant: the backward check once more
    // (SelectionOptions::backward_after_tau).
    if (o.backward_after_tau && moved) {
      Q = span::orthonormal(X);
      r = y - Q * (Q.transpose() * y);
      const std::size_t kept = chosen.size();
      backward_check();
      if (chosen.size() != kept) {  // the path's summary without it
        res.cv_sse = cv_prev;
        summary.rss = r.squaredNorm();
      }
    }
  }
  fit_chosen(pb, X, y, Qd, {chosen, ambiguous, separations, n_datum}, res);
  return res;
}

}  // namespace abbe::diagnose
