#include "time_constant.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <cstdint>

#include "abbe/diagnose/selection.hpp"
#include "span.hpp"

namespace abbe::diagnose::selection {

std::pair<double, double> best_time_constant(const Problem& pb, const Mat& Q, const Vec& r,
                                             const Term& drift, double lo, double hi) {
  // What the drift at τ = e^u removes (−: Brent minimises).
  auto lost = [&](double u) {
    Term t = drift;
    t.tau_s = std::exp(u);
    const Mat C = term_columns(pb, t);
    return -delta_rss(C, C.transpose() * C, Q.transpose() * C, r);
  };
  // ln τ to 2⁻¹⁶ (τ to 0.002 %: far inside its uncertainty, a few % where
  // a drift is named; each step is a column of every observation).
  constexpr int kBits = 16;
  std::uintmax_t iterations = 60;
  const auto [u, best] =
      boost::math::tools::brent_find_minima(lost, std::log(lo), std::log(hi), kBits, iterations);
  return {std::exp(u), -best};
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
  c.C = term_columns(pb, c.term);
  c.CtC = c.C.transpose() * c.C;
  c.QtC = Q.transpose() * c.C;
  return d_best;
}

void refine_time_constants(const Problem& pb, Mat& X, const Vec& y, std::vector<Term>& chosen,
                           std::vector<std::string>& log) {
  std::vector<Eigen::Index> start(chosen.size());
  Eigen::Index columns = 0;
  for (std::size_t i = 0; i < chosen.size(); ++i) {
    start[i] = columns;
    columns += chosen[i].columns();
  }
  if (columns != X.cols()) return;  // not the chosen terms' columns: leave them
  for (std::size_t i = 0; i < chosen.size(); ++i) {
    Term& drift = chosen[i];
    if (drift.kind != TermKind::thermal_drift || !(drift.tau_s > 0.0)) continue;
    // Everything else of the named stage, and the data beside it.
    Eigen::Index others = 0;
    for (std::size_t j = 0; j < chosen.size(); ++j)
      if (j != i && chosen[j].kind != TermKind::unexplained) others += chosen[j].columns();
    Mat A(X.rows(), others);
    Eigen::Index c = 0;
    for (std::size_t j = 0; j < chosen.size(); ++j)
      if (j != i && chosen[j].kind != TermKind::unexplained) {
        A.middleCols(c, chosen[j].columns()) = X.middleCols(start[j], chosen[j].columns());
        c += chosen[j].columns();
      }
    const Mat Q = span::orthonormal(A);
    const Vec r = y - Q * (Q.transpose() * y);
    const Mat C = X.middleCols(start[i], drift.columns());
    const double before = delta_rss(C, C.transpose() * C, Q.transpose() * C, r);
    const auto [tau_best, after] =
        best_time_constant(pb, Q, r, drift, 0.5 * drift.tau_s, 2.0 * drift.tau_s);
    if (!(after > before)) continue;
    const double tau_before = drift.tau_s;
    drift.tau_s = tau_best;
    X.middleCols(start[i], drift.columns()) = term_columns(pb, drift);
    log.push_back(fmt::format("final fit: {} τ {:.6g} s → {:.6g} s (ΔRSS {:.6g} → {:.6g})",
                              drift.label(), tau_before, drift.tau_s, before, after));
  }
}

}  // namespace abbe::diagnose::selection
