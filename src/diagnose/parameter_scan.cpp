#include "parameter_scan.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

#include "abbe/diagnose/selection.hpp"
#include "abbe/io/units.hpp"

namespace abbe::diagnose::selection {

Term scan_parameter(const ScanFamily& f, const ScanInput& in, PowerCache& power_cache,
                    std::vector<double>& aliases) {
  const Problem& pb = in.pb;
  const Mat& R = in.R;
  const Mat& W = in.W;
  const std::vector<std::size_t>& set_of = in.set_of;
  const std::size_t stride = in.stride;
  const double alias_power = in.alias_power;
  const std::size_t np = pb.points.size();
  Term t = f.base;
  if (t.kind == TermKind::cyclic) {
    const auto j = static_cast<std::size_t>(t.axis);
    auto& acc = power_cache[j];
    if (acc.empty()) {
      // Σ_p R(p,i)·exp(i2πf s_j) over the frequency grid (shared by the three directions).
      const std::size_t nf = f.grid.size();
      acc.assign(6 * nf, 0.0);
      const double f0 = 1.0 / f.grid.front();
      const double df = nf > 1 ? 1.0 / f.grid[1] - f0 : 0.0;
      for (std::size_t p = 0; p < np; p += stride) {
        const double s = pb.points[p].s[t.axis];
        // z = exp(i2πf s) stepped through the grid by the factor exp(i2π·df·s).
        double zr = std::cos(units::kTwoPi * f0 * s), zi = std::sin(units::kTwoPi * f0 * s);
        const double mr = std::cos(units::kTwoPi * df * s), mi = std::sin(units::kTwoPi * df * s);
        const auto ip = static_cast<Eigen::Index>(p);
        const double r0 = R(ip, 0), r1 = R(ip, 1), r2 = R(ip, 2);
        double* a = acc.data();
        for (std::size_t q = 0; q < nf; ++q, a += 6) {
          a[0] += r0 * zr;
          a[1] += r0 * zi;
          a[2] += r1 * zr;
          a[3] += r1 * zi;
          a[4] += r2 * zr;
          a[5] += r2 * zi;
          const double nr = zr * mr - zi * mi;
          zi = zr * mi + zi * mr;
          zr = nr;
        }
      }
    }
    // Frequencies within the resolution 1/span of a chosen cycle of the
    // same axis and direction (ScanInput::chosen_cycles) are not scanned.
    const double resolution = 1.0 / std::max(pb.var_hi[j] - pb.var_lo[j], 1e-3);
    auto resolved_from_chosen = [&](double period) {
      if (!in.chosen_cycles) return true;
      for (const Term& c : *in.chosen_cycles)
        if (c.kind == TermKind::cyclic && c.axis == t.axis && c.direction == t.direction &&
            c.period_mm > 0.0 && std::abs(1.0 / period - 1.0 / c.period_mm) < resolution)
          return false;
      return true;
    };
    std::size_t best = 0;
    double best_pow = -1.0;
    std::vector<double> pow(f.grid.size());
    for (std::size_t q = 0; q < f.grid.size(); ++q) {
      const std::size_t at = 6 * q + 2 * static_cast<std::size_t>(t.direction);
      const double pw = acc[at] * acc[at] + acc[at + 1] * acc[at + 1];
      pow[q] = pw;
      if (pw > best_pow && resolved_from_chosen(f.grid[q])) {
        best_pow = pw;
        best = q;
      }
    }
    t.period_mm = f.grid[best];
    // The peak between the grid's frequencies: a parabola through the
    // best power and its two neighbours (a period a quarter step off
    // beats against the data over a long travel).
    if (in.refine_period && best > 0 && best + 1 < pow.size()) {
      const double pm = pow[best - 1], p0 = pow[best], pp = pow[best + 1];
      const double curv = pm - 2.0 * p0 + pp;
      if (curv < 0.0) {
        const double delta = std::clamp(0.5 * (pm - pp) / curv, -0.5, 0.5);
        const double fb = 1.0 / f.grid[best];
        const double step = 1.0 / f.grid[best + 1] - fb;
        t.period_mm = 1.0 / (fb + delta * step);
      }
    }
    // Aliases: other peaks (local maxima away from the best) that reach
    // nearly the same power — on regularly spaced levels a period and its
    // aliases give the same samples, and the design cannot tell them apart.
    for (std::size_t q = 1; q + 1 < pow.size(); ++q) {
      const std::size_t gap = q > best ? q - best : best - q;
      if (gap <= 4 || pow[q] < pow[q - 1] || pow[q] < pow[q + 1]) continue;
      if (pow[q] >= alias_power * best_pow) aliases.push_back(f.grid[q]);
    }
  } else {  // thermal_drift: the time constant with the largest normalised projection
    // The residual is orthogonal to the datum's offsets, so the
    // column's norm is taken without its mean per set (else a time
    // constant whose column has the larger mean is penalised, and the
    // scan prefers the wrong shape).
    double best_score = -1.0;
    const std::size_t ns = std::max<std::size_t>(pb.sets.size(), 1);
    std::vector<double> sw(ns), swg(ns);
    for (double tau : f.grid) {
      double num = 0.0, den = 0.0;
      std::fill(sw.begin(), sw.end(), 0.0);
      std::fill(swg.begin(), swg.end(), 0.0);
      for (std::size_t p = 0; p < np; p += stride) {
        const PointContext& pc = pb.points[p];
        const double tt = std::max(pc.t, 0.0);
        double g = tau > 0.0 ? 1.0 - std::exp(-tt / tau) : tt / 3600.0;
        if (t.with_axis >= 0) g *= 1e-3 * pc.s[t.with_axis];
        const auto ip = static_cast<Eigen::Index>(p);
        const double w = W(ip, t.direction);
        num += R(ip, t.direction) * g;
        den += w * g * g;
        sw[set_of[p]] += w;
        swg[set_of[p]] += w * g;
      }
      for (std::size_t k = 0; k < ns; ++k)
        if (sw[k] > 0.0) den -= swg[k] * swg[k] / sw[k];
      const double score = den > 0.0 ? num * num / den : 0.0;
      if (score > best_score) {
        best_score = score;
        t.tau_s = tau;
      }
    }
  }
  return t;
}

std::pair<double, double> brent_maximum(const std::function<double(double)>& f, double lo,
                                        double hi, int bits) {
  std::uintmax_t iterations = 60;
  const auto [x, lost] = boost::math::tools::brent_find_minima([&](double v) { return -f(v); }, lo,
                                                               hi, bits, iterations);
  return {x, -lost};
}

FrequencyRange frequency_range(const ScanFamily& f) {
  if (f.grid.empty()) return {};
  const auto [shortest, longest] = std::minmax_element(f.grid.begin(), f.grid.end());
  return {1.0 / *longest, 1.0 / *shortest};
}

double refine_period_exactly(const Problem& pb, const Mat& Q, const Vec& r, double half_step,
                             Cached& c, FrequencyRange range, bool aliases_at_range_end) {
  const double d_scan = delta_rss(c.C, c.CtC, c.QtC, r);
  if (c.term.kind != TermKind::cyclic || !(c.term.period_mm > 0.0) || !(half_step > 0.0))
    return d_scan;
  const double f_scan = 1.0 / c.term.period_mm;
  auto removes_at = [&](double f) {
    Term t = c.term;
    t.period_mm = 1.0 / f;
    return removes(pb, t, Q, r);
  };
  // On [f − h, f + h] (the frequency stays positive). On few or irregular
  // levels what a cycle removes can have more than one local maximum
  // within one grid step, so the interval is first sampled at 9
  // frequencies; then Brent between the best sample's neighbours, to the
  // precision a double allows (2⁻²⁵ of f: over a 1 m travel a period of
  // 16 mm is placed to a few 10⁻⁶ of a cycle).
  constexpr int kSamples = 9;
  // Never beyond the family's frequency grid: a period the catalogue does
  // not search is not named by refining one at its end.
  const double lo = std::max({f_scan - half_step, 0.5 * f_scan, range.lo}),
               hi = std::min(f_scan + half_step, range.hi);
  if (!(hi > lo)) return d_scan;
  const double step = (hi - lo) / (kSamples - 1);
  int k_best = 0;
  double g_sampled = -1.0;
  for (int k = 0; k < kSamples; ++k) {
    const double g = removes_at(lo + k * step);
    if (g > g_sampled) {
      g_sampled = g;
      k_best = k;
    }
  }
  const auto [f_brent, g_brent] = brent_maximum(removes_at, lo + std::max(k_best - 1, 0) * step,
                                                lo + std::min(k_best + 1, kSamples - 1) * step,
                                                std::numeric_limits<double>::digits / 2);
  const bool brent_better = g_brent >= g_sampled;
  double f_best = brent_better ? f_brent : lo + k_best * step;
  double g_best = brent_better ? g_brent : g_sampled;
  // Stopped at the end of the range: the best lies beyond it, where the
  // catalogue does not search; on regular levels the periods the scan found
  // as good (c.aliases) give nearly the same samples within the range, so
  // each is refined too and the best kept (a pitch error of Z on the grid's
  // 5 levels, held at 100 mm, fitted worse than its alias at 16.2 mm).
  const bool at_end = f_best <= range.lo * (1.0 + 1e-9) || f_best >= range.hi * (1.0 - 1e-9);
  if (aliases_at_range_end && at_end)
    for (double period : c.aliases) {
      if (!(period > 0.0) || std::abs(1.0 / period - f_scan) <= 1e-12 * f_scan) continue;
      Term t = c.term;
      t.period_mm = period;
      Cached a = cached(pb, t, Q);
      const double d = refine_period_exactly(pb, Q, r, half_step, a, range, false);
      if (d > g_best) {
        g_best = d;
        f_best = 1.0 / a.term.period_mm;
      }
    }
  if (!(g_best > d_scan)) return d_scan;
  c.term.period_mm = 1.0 / f_best;
  c = cached(pb, c.term, Q, std::move(c.aliases));
  return g_best;
}

void confirm_aliases(const Problem& pb, const Mat& Q, const Vec& r, double half_step, double d_pick,
                     double margin, Cached& c, FrequencyRange range) {
  if (c.term.kind != TermKind::cyclic) return;
  std::vector<double> kept;
  for (double period : c.aliases) {
    Term t = c.term;
    t.period_mm = period;
    Cached a = cached(pb, t, Q);
    const double d = refine_period_exactly(pb, Q, r, half_step, a, range);
    if (d_pick - d < margin) kept.push_back(a.term.period_mm);
  }
  c.aliases = std::move(kept);
}

}  // namespace abbe::diagnose::selection
