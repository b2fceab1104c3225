#include "time_constant.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "abbe/diagnose/selection.hpp"
#include "parameter_scan.hpp"
#include "span.hpp"

namespace abbe::diagnose::selection {

std::pair<double, double> best_time_constant(const Problem& pb, const Mat& Q, const Vec& r,
                                             const Term& drift, double lo, double hi) {
  // What the drift at τ = e^u removes.
  auto removes_at = [&](double u) {
    Term t = drift;
    t.tau_s = std::exp(u);
    return removes(pb, t, Q, r);
  };
  // ln τ to 2⁻¹⁶ (τ to 0.002 %: far inside its uncertainty, a few % where
  // a drift is named; each step is a column of every observation).
  constexpr int kBits = 16;
  const auto [u, best] = brent_maximum(removes_at, std::log(lo), std::log(hi), kBits);
  return {std::exp(u), best};
}

double refine_tau_exactly(const Problem& pb, const Mat& Q, const Vec& r,
                          const std::vector<double>& grid, Cached& c) {
  const double d_scan = delta_rss(c.C, c.CtC, c.QtC, r);
  const double tau = c.term.tau_s;
  if (c.term.kind != TermKind::thermal_drift || !(tau > 0.0)) return d_scan;
  // The grid's neighbours of τ (half and twice τ past its ends).
  double lo = 0.5 * tau, hi = 2.0 * tau;
  for (double g : grid) {
    if (g > 0.0 && g < tau) lo = std::max(lo, g);
    if (g > tau) hi = std::min(hi, g);
  }
  const auto [tau_best, d_best] = best_time_constant(pb, Q, r, c.term, lo, hi);
  if (!(d_best > d_scan)) return d_scan;
  c.term.tau_s = tau_best;
  c = cached(pb, c.term, Q, std::move(c.aliases));
  return d_best;
}

bool refine_time_constants(const Problem& pb, Mat& X, const Vec& y, std::vector<Term>& chosen,
                           std::vector<std::string>& log) {
  // Each chosen term's columns, as X holds them side by side.
  std::vector<Mat> blocks;
  std::vector<Eigen::Index> start;
  Eigen::Index columns = 0;
  for (const Term& t : chosen) {
    if (columns + t.columns() > X.cols()) return false;  // not the chosen terms' columns
    start.push_back(columns);
    blocks.emplace_back(X.middleCols(columns, t.columns()));
    columns += t.columns();
  }
  if (columns != X.cols()) return false;
  const Mat none(X.rows(), 0);
  bool moved = false;
  for (std::size_t i = 0; i < chosen.size(); ++i) {
    Term& drift = chosen[i];
    if (drift.kind != TermKind::thermal_drift || !(drift.tau_s > 0.0)) continue;
    // Everything else of the named stage, and the data beside it.
    std::vector<bool> others(chosen.size());
    for (std::size_t j = 0; j < chosen.size(); ++j)
      others[j] = j != i && chosen[j].kind != TermKind::unexplained;
    const Mat Q = span::basis_of(none, blocks, others);
    const Vec r = span::residual_of(Q, y);
    const Mat& C = blocks[i];
    const double before = delta_rss(C, C.transpose() * C, Q.transpose() * C, r);
    const auto [tau_best, after] =
        best_time_constant(pb, Q, r, drift, 0.5 * drift.tau_s, 2.0 * drift.tau_s);
    if (!(after > before)) continue;
    const double tau_before = drift.tau_s;
    drift.tau_s = tau_best;
    blocks[i] = term_columns(pb, drift);
    X.middleCols(start[i], drift.columns()) = blocks[i];
    log.push_back(fmt::format("final fit: {} τ {:.6g} s → {:.6g} s (ΔRSS {:.6g} → {:.6g})",
                              drift.label(), tau_before, drift.tau_s, before, after));
    moved = true;
  }
  return moved;
}

}  // namespace abbe::diagnose::selection
