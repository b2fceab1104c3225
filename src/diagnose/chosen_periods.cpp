#include "chosen_periods.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>

#include "final_refit.hpp"
#include "parameter_scan.hpp"

namespace abbe::diagnose::selection {

bool refine_chosen_periods(const Problem& pb, const CandidateSet& cs, Mat& X, const Vec& y,
                           std::vector<Term>& chosen, std::vector<std::string>& log) {
  FinalRefit how;
  how.applies = [](const Term& t) {
    return t.kind == TermKind::cyclic && t.axis >= 0 && t.period_mm > 0.0;
  };
  how.refine = [&](const Term& cycle, const Mat& Q, const Vec& r) -> std::pair<Term, double> {
    const auto j = static_cast<std::size_t>(cycle.axis);
    const double span = pb.var_hi[j] - pb.var_lo[j];
    if (!(span > 0.0)) return {cycle, 0.0};
    // Within the frequencies its family searches (the catalogue's periods,
    // CandidateOptions::max_period_span_share).
    FrequencyRange family;
    for (const ScanFamily& f : cs.scanned)
      if (f.base.kind == TermKind::cyclic && f.base.axis == cycle.axis &&
          f.base.direction == cycle.direction)
        family = frequency_range(f);
    const double f0 = 1.0 / cycle.period_mm, half = 0.5 / span;
    const double lo = std::max({f0 - half, 0.5 * f0, family.lo}),
                 hi = std::min(f0 + half, family.hi);
    if (!(hi > lo)) return {cycle, 0.0};
    auto removes_at = [&](double f) {
      Term t = cycle;
      t.period_mm = 1.0 / f;
      return removes(pb, t, Q, r);
    };
    const auto [f_best, after] =
        brent_maximum(removes_at, lo, hi, std::numeric_limits<double>::digits / 2);
    Term t = cycle;
    t.period_mm = 1.0 / f_best;
    return {t, after};
  };
  how.describe = [](const Term& a, const Term& b, double before, double after) {
    return fmt::format("final fit: {} period {:.6g} mm → {:.6g} mm (ΔRSS {:.6g} → {:.6g})",
                       b.label(), a.period_mm, b.period_mm, before, after);
  };
  return refine_each_beside_others(pb, X, y, chosen, how, log);
}

}  // namespace abbe::diagnose::selection
