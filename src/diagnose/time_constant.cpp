#include "time_constant.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "abbe/diagnose/selection.hpp"
#include "final_refit.hpp"
#include "parameter_scan.hpp"

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
  FinalRefit how;
  how.applies = [](const Term& t) { return t.kind == TermKind::thermal_drift && t.tau_s > 0.0; };
  how.refine = [&](const Term& drift, const Mat& Q, const Vec& r) -> std::pair<Term, double> {
    const auto [tau_best, after] =
        best_time_constant(pb, Q, r, drift, 0.5 * drift.tau_s, 2.0 * drift.tau_s);
    Term t = drift;
    t.tau_s = tau_best;
    return {t, after};
  };
  how.describe = [](const Term& a, const Term& b, double before, double after) {
    return fmt::format("final fit: {} τ {:.6g} s → {:.6g} s (ΔRSS {:.6g} → {:.6g})", b.label(),
                       a.tau_s, b.tau_s, before, after);
  };
  return refine_each_beside_others(pb, X, y, chosen, how, log);
}

}  // namespace abbe::diagnose::selection
