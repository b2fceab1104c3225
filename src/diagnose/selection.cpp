#include "abbe/diagnose/selection.hpp"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <random>

#include "abbe/diagnose/separation.hpp"
#include "abbe/diagnose/statistics.hpp"
#include "backward_check.hpp"
#include "candidate_fit.hpp"
#include "final_fit.hpp"
#include "parameter_scan.hpp"
#include "path.hpp"
#include "revisit.hpp"
#include "span.hpp"
#include "structure.hpp"

namespace abbe::diagnose {
using selection::abs_correlation;
using selection::Cached;
using selection::delta_rss;
using selection::fit_chosen;
using selection::generic_basis;
using selection::Mat;
using selection::motion_squared;
using selection::point_sums;
using selection::Score;
using selection::Step;
using selection::StructureChoice;
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

  // Named candidates without a searched parameter: columns cached once.
  // The datum: always in the fit, before any effect.
  Mat Q(n, 0);
  Mat X(n, 0);
  std::vector<Term> chosen;
  std::vector<std::vector<std::string>> ambiguous;
  std::vector<std::string> separations;  // per chosen term: what would tell it from its rivals
  std::vector<int> step_of;              // per chosen term: its step (−1: the datum)
  for (const Term& t : cs.datum) {
    const Mat C = term_columns(pb, t);
    // Invisible in these data: the measured directions see (almost) none of
    // what the term moves — e.g. the rotation of a circle measured along
    // its radius, seen only through the rounding of the file's numbers.
    if (!(C.squaredNorm() > 1e-6 * motion_squared(pb, t))) continue;
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

  std::vector<Cached> named;
  for (const Term& t : cs.fixed) {
    Cached c{t, term_columns(pb, t), Mat(), Mat(), {}};
    c.QtC = Q.transpose() * c.C;
    c.CtC = c.C.transpose() * c.C;
    if (c.CtC.diagonal().maxCoeff() <= 0.0) continue;  // invisible in these data
    named.push_back(std::move(c));
  }
  // Smooth families: point-level Gram matrices per direction, once.
  struct Generic {
    Term term;
    std::array<Mat, 3> G;
  };
  std::vector<Generic> generic;
  {
    Mat R, W;
    point_sums(pb, y, R, W);
    for (const Term& t : cs.generic) {
      Generic g{t, {}};
      const Mat B = generic_basis(pb, t);
      for (int i = 0; i < 3; ++i)
        if (pb.direction_present[static_cast<std::size_t>(i)])
          g.G[static_cast<std::size_t>(i)] = B.transpose() * W.col(i).asDiagonal() * B;
      generic.push_back(std::move(g));
    }
  }

  // The set of each point (its index in pb.sets).
  std::vector<std::size_t> set_of(np, 0);
  for (std::size_t p = 0; p < np; ++p) {
    const auto it = std::find(pb.sets.begin(), pb.sets.end(), pb.points[p].set);
    set_of[p] = it == pb.sets.end() ? 0 : static_cast<std::size_t>(it - pb.sets.begin());
  }
  const double tests_named = std::max(cs.named_tests, 1);
  const double tests_generic = std::max(cs.generic_tests, 1);
  // Subsample for the period scan.
  const std::size_t stride = std::max<std::size_t>(1, (np + o.scan_points - 1) / o.scan_points);

  std::array<double, 64> practical_cache{};                  // by column count
  std::map<std::string, std::array<double, 3>> share_cache;  // by label: share along each direction
  for (int step = 0; step < o.max_terms; ++step) {
    if (o.on_step) o.on_step(step);
    const double rr = r.squaredNorm();
    const double dof_base = static_cast<double>(n - Q.cols());
    if (dof_base < 4.0) break;
    // The practical floor in units of σ̂²: an effect that removes exactly
    // n·(f·σ̂)² would give ΔRSS/σ̂² ~ χ²_k(λ = n·f²) (its noise adds k and
    // scatters it); the candidate must exceed that distribution's upper α
    // quantile, so that its effect is shown above the floor, not only
    // estimated there (min_effect_test; else ΔRSS ≥ n·f²·σ̂²).
    const double lambda = static_cast<double>(n) * o.min_effect_rms * o.min_effect_rms;
    auto practical = [&](int k) {
      if (!o.min_effect_test) return lambda;
      // Cached per column count below 64 (n is fixed); a wider candidate
      // (a large smooth family) gets its own quantile.
      if (k >= static_cast<int>(practical_cache.size()))
        return noncentral_chi2_upper_quantile(k, lambda, o.alpha);
      double& q = practical_cache[static_cast<std::size_t>(k)];
      if (q <= 0.0) q = noncentral_chi2_upper_quantile(k, lambda, o.alpha);
      return q;
    };

    Term pick;
    Mat C;
    double d_pick = 0.0;
    std::vector<std::string> amb;
    std::string separation;
    std::vector<Term> with_pick;  // the partners of a winning combination
    std::vector<std::vector<std::string>> with_amb;
    std::vector<std::string> with_separation;
    std::vector<Cached> scanned;
    std::vector<Score> scores;
    const Score* best_named = nullptr;
    if (forced_first && step == 0) {
      pick = *forced_first;
      C = term_columns(pb, pick);
      d_pick = selection::removed_by(C, Q, r);
    } else {
      Mat R, W;
      point_sums(pb, r, R, W);
      // Searched families: pick the parameter by a quick projection, then
      // evaluate the best of each family exactly.
      selection::PowerCache power_cache;
      const selection::ScanInput scan_in{pb, R, W, set_of, stride, o.alias_power, o.refine_period};
      for (const ScanFamily& f : cs.scanned) {
        std::vector<double> aliases;
        const Term t = scan_parameter(f, scan_in, power_cache, aliases);
        Cached c{t, term_columns(pb, t), Mat(), Mat(), std::move(aliases)};
        c.CtC = c.C.transpose() * c.C;
        c.QtC = Q.transpose() * c.C;
        scanned.push_back(std::move(c));
      }

      // Best named candidate.
      auto consider = [&](const Cached& c) {
        const double d = delta_rss(c.C, c.CtC, c.QtC, r);
        if (d <= 0.0) return;
        const int k = c.term.columns();
        const double s2 = std::max(rr - d, 1e-300) / std::max(dof_base - k, 1.0);
        const double chi2 = chi2_upper_quantile(k, o.alpha / tests_named);
        scores.push_back({&c, d, s2 * std::max(chi2, practical(k))});
      };
      for (const Cached& c : named) consider(c);
      for (const Cached& c : scanned) consider(c);
      std::sort(scores.begin(), scores.end(),
                [](const Score& a, const Score& b) { return a.d > b.d; });
      // σ̂² of the information criterion: the least residual variance any
      // candidate leaves (a structure still in the residual does not inflate it).
      double s2_ic = rr / dof_base;
      for (const Score& s : scores)
        s2_ic = std::min(
            s2_ic, std::max(rr - s.d, 1e-300) / std::max(dof_base - s.c->term.columns(), 1.0));
      // The smooth function's fields are set once it is found (below).
      Step step_view(pb, o, cs, Q, r, scores, share_cache);
      step_view.rr = rr;
      step_view.dof_base = dof_base;
      step_view.lambda = lambda;
      step_view.tests_named = tests_named;
      step_view.s2_ic = s2_ic;
      for (const Score& s : scores)
        if (s.d > s.thr) {
          best_named = &s;
          break;
        }
      best_named = step_view.parsimonious(best_named);

      // Best smooth function (approximate: not orthogonalised against Q, so it
      // never overstates what it explains).
      double g_best_excess = 0.0, g_best_d = 0.0;
      Term g_best;
      bool have_generic = false;
      for (const Generic& g : generic) {
        const Mat B = generic_basis(pb, g.term);
        const Mat BtR = B.transpose() * R;
        for (int i = 0; i < 3; ++i) {
          if (!pb.direction_present[static_cast<std::size_t>(i)]) continue;
          const Mat& G = g.G[static_cast<std::size_t>(i)];
          const Vec b = BtR.col(i);
          Eigen::LDLT<Mat> ldlt(G);
          const double d = b.dot(ldlt.solve(b));
          const int k = g.term.columns();
          const double s2 = std::max(rr - d, 1e-300) / std::max(dof_base - k, 1.0);
          const double thr =
              s2 * std::max(chi2_upper_quantile(k, o.alpha / tests_generic), practical(k));
          if (d > thr && d - thr > g_best_excess) {
            g_best_excess = d - thr;
            g_best_d = d;
            g_best = g.term;
            g_best.direction = i;
            have_generic = true;
          }
        }
      }

      // Before the smooth function is taken: does a named part of its
      // structure, alone or with up to two partners, explain it as well at a
      // lower cost (docs/diagnosis.md, step 3)?
      step_view.have_generic = have_generic;
      step_view.g_best = g_best;
      step_view.g_best_d = g_best_d;
      StructureChoice structure;
      explain_structure(step_view, best_named, step, structure, res.log);
      if (structure.lead_explains || structure.combination_wins) best_named = structure.lead;
      // The chosen cycles' periods on the exact ΔRSS (after the choice, so
      // that the finer period does not give a cycle an edge over the fixed
      // candidates it competed with: on a few regular levels every period is
      // an alias, and a freer one fits the noise).
      if (o.exact_period && best_named) {
        auto refine = [&](const Score* s) {
          if (s->c->term.kind != TermKind::cyclic) return;
          // A cycle is a scanned candidate: scanned[i] of family cs.scanned[i].
          const auto i = static_cast<std::size_t>(s->c - scanned.data());
          const std::vector<double>& grid = cs.scanned[i].grid;
          if (grid.size() < 2) return;
          scores[static_cast<std::size_t>(s - scores.data())].d = selection::refine_period_exactly(
              pb, Q, r, std::abs(1.0 / grid[1] - 1.0 / grid[0]), scanned[i]);
        };
        refine(best_named);
        for (const Score* s : structure.partners) refine(s);
      }

      if (best_named && (!have_generic || structure.combination_wins || structure.lead_explains ||
                         best_named->d >= o.name_ratio * g_best_d)) {
        pick = best_named->c->term;
        C = best_named->c->C;
        d_pick = best_named->d;
        separation = step_view.rivals(*best_named, amb);
        // A combination that won against a smooth function enters whole: its
        // members explain the structure together (a partner alone may be
        // below the practical floor, e.g. the squareness part of an
        // off-centre coupling), so each is kept with it, with its own rivals.
        for (std::size_t m = 0; m < structure.partners.size(); ++m) {
          const Score* s = structure.partners[m];
          const std::vector<Term>& swapped_in = structure.partner_rivals[m];
          Mat Cn(n, C.cols() + s->c->C.cols());
          Cn << C, s->c->C;
          C = std::move(Cn);
          with_pick.push_back(s->c->term);
          with_amb.emplace_back();
          std::string sep = step_view.rivals(*s, with_amb.back());
          for (const Term& t : swapped_in)
            if (std::find(with_amb.back().begin(), with_amb.back().end(), t.label()) ==
                with_amb.back().end())
              with_amb.back().push_back(t.label());
          if (sep.empty() && !swapped_in.empty())
            sep = separating_measurement(s->c->term, swapped_in, {});
          with_separation.push_back(sep);
        }
        if (!structure.partners.empty()) d_pick = structure.d_partners;
      } else if (have_generic) {
        pick = g_best;
        C = term_columns(pb, pick);
        d_pick = g_best_d;
      } else {
        res.log.push_back(
            fmt::format("step {}: no candidate above the significance floor", step + 1));
        break;
      }

      // The first step's near alternatives, for the revisit (revisit.hpp).
      if (step == 0 && pick.kind != TermKind::unexplained && with_pick.empty())
        first_step_alternatives(pb, cs, o, Q, r, scores, pick, d_pick, summary.first_alternatives);
    }

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
    if (!(cv < cv_prev * (1.0 - 1e-6)) && pick.kind == TermKind::unexplained && best_named) {
      res.log.push_back(fmt::format("step {}: {} rejected: held-out SSE {:.6g} ≥ {:.6g}", step + 1,
                                    pick.label(), cv, cv_prev));
      pick = best_named->c->term;
      C = best_named->c->C;
      d_pick = best_named->d;
      amb.clear();
      separation.clear();
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
    for (const Term& t : with_pick) picked += " + " + t.label();
    res.log.push_back(fmt::format("step {}: {} ΔRSS {:.6g} (of {:.6g}), held-out SSE {:.6g}",
                                  step + 1, picked, d_pick, rr, cv));
    cv_prev = cv;
    X = std::move(Xn);
    const Eigen::Index p0 = Q.cols();
    append_orthonormal(Q, C);
    const Mat Qnew = Q.rightCols(Q.cols() - p0);
    r -= Qnew * (Qnew.transpose() * r);
    for (Cached& c : named) {
      Mat ext(Q.cols(), c.C.cols());
      ext << c.QtC, Qnew.transpose() * c.C;
      c.QtC = std::move(ext);
    }
    chosen.push_back(pick);
    ambiguous.push_back(amb);
    separations.push_back(separation);
    step_of.push_back(step);
    if (step == 0 && with_pick.empty() && pick.kind != TermKind::unexplained) summary.first = pick;
    for (std::size_t i = 0; i < with_pick.size(); ++i) {
      chosen.push_back(with_pick[i]);
      ambiguous.push_back(with_amb[i]);
      separations.push_back(with_separation[i]);
      step_of.push_back(step);
    }
    // A chosen fixed candidate cannot be chosen again.
    named.erase(std::remove_if(named.begin(), named.end(),
                               [&](const Cached& c) {
                                 if (c.term.label() == pick.label()) return true;
                                 for (const Term& t : with_pick)
                                   if (c.term.label() == t.label()) return true;
                                 return false;
                               }),
                named.end());
  }

  // The backward check (backward_check.hpp): a named effect that the ones
  // chosen after it made redundant leaves the fit, the weakest first.
  while (o.backward_check && chosen.size() > n_datum) {
    const double dof = static_cast<double>(n - Q.cols());
    if (dof < 1.0) break;
    const auto weak = selection::least_needed_named(X, Qd, y, chosen, n_datum,
                                                    r.squaredNorm() / dof, o.alpha / tests_named);
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

  // Final joint fit of every chosen term.
  res.cv_sse = cv_prev;
  res.residual = r;
  summary.rss = r.squaredNorm();
  if (chosen.size() == n_datum) {
    res.sigma_um =
        std::sqrt(r.squaredNorm() / std::max<double>(static_cast<double>(n - X.cols()), 1.0));
    if (chosen.empty()) return res;
  }
  fit_chosen(pb, X, y, Qd, {chosen, ambiguous, separations, n_datum}, res);
  return res;
}

}  // namespace abbe::diagnose
