#include "chosen_periods.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>

#include "parameter_scan.hpp"
#include "span.hpp"

namespace abbe::diagnose::selection {

bool refine_chosen_periods(const Problem& pb, const CandidateSet& cs, Mat& X, const Vec& y,
                           std::vector<Term>& chosen, std::vector<std::string>& log) {
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
    Term& cycle = chosen[i];
    if (cycle.kind != TermKind::cyclic || cycle.axis < 0 || !(cycle.period_mm > 0.0)) continue;
    const auto j = static_cast<std::size_t>(cycle.axis);
    const double span = pb.var_hi[j] - pb.var_lo[j];
    if (!(span > 0.0)) continue;
    std::vector<bool> others(chosen.size());
    for (std::size_t k = 0; k < chosen.size(); ++k)
      others[k] = k != i && chosen[k].kind != TermKind::unexplained;
    const Mat Q = span::basis_of(none, blocks, others);
    const Vec r = span::residual_of(Q, y);
    const Mat& C = blocks[i];
    const double before = delta_rss(C, C.transpose() * C, Q.transpose() * C, r);
    // Within the frequencies its family searches (the catalogue's periods,
    // CandidateOptions::max_period_span_share).
    double f_lo = 0.0, f_hi = std::numeric_limits<double>::infinity();
    for (const ScanFamily& f : cs.scanned)
      if (f.base.kind == TermKind::cyclic && f.base.axis == cycle.axis &&
          f.base.direction == cycle.direction && !f.grid.empty()) {
        f_lo = 1.0 / std::max(f.grid.front(), f.grid.back());
        f_hi = 1.0 / std::min(f.grid.front(), f.grid.back());
      }
    const double f0 = 1.0 / cycle.period_mm, half = 0.5 / span;
    const double lo = std::max({f0 - half, 0.5 * f0, f_lo}), hi = std::min(f0 + half, f_hi);
    if (!(hi > lo)) continue;
    auto removes_at = [&](double f) {
      Term t = cycle;
      t.period_mm = 1.0 / f;
      return removes(pb, t, Q, r);
    };
    const auto [f_best, after] =
        brent_maximum(removes_at, lo, hi, std::numeric_limits<double>::digits / 2);
    if (!(after > before)) continue;
    const double period_before = cycle.period_mm;
    cycle.period_mm = 1.0 / f_best;
    blocks[i] = term_columns(pb, cycle);
    X.middleCols(start[i], cycle.columns()) = blocks[i];
    log.push_back(fmt::format("final fit: {} period {:.6g} mm → {:.6g} mm (ΔRSS {:.6g} → {:.6g})",
                              cycle.label(), period_before, cycle.period_mm, before, after));
    moved = true;
  }
  return moved;
}

}  // namespace abbe::diagnose::selection
