#include "cycle_period_test.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "abbe/io/units.hpp"
#include "swap_test.hpp"

namespace abbe::diagnose {
namespace design {
namespace {

// No level left out (cycle_at_levels, OtherPeriods).
constexpr std::size_t kNoLevel = static_cast<std::size_t>(-1);

// The cycle at frequency f on the levels lv (levels × 2); 0 at the level
// `skip`, which then takes no part in its fit.
Mat cycle_at_levels(const std::vector<double>& lv, double f, std::size_t skip) {
  Mat V(static_cast<Eigen::Index>(lv.size()), 2);
  for (std::size_t l = 0; l < lv.size(); ++l) {
    const double w = units::kTwoPi * f * lv[l];
    V(static_cast<Eigen::Index>(l), 0) = l == skip ? 0.0 : std::sin(w);
    V(static_cast<Eigen::Index>(l), 1) = l == skip ? 0.0 : std::cos(w);
  }
  return V;
}

// The other periods of the catalogue's range, away from `period_mm`'s main
// lobe (1/span in frequency), on the levels lv, and what each one's cycle
// removes in place (ip): the scan's local peaks at 1/8 of the main lobe,
// each refined on a grid 20 times finer (an alias fits exactly only at its
// frequency).
class OtherPeriods {
 public:
  OtherPeriods(const LevelSpan::InPlace& ip, const std::vector<double>& lv, double period_mm,
               const DesignAmbiguityOptions& o, double min_period_mm)
      : ip_(ip),
        lv_(lv),
        span_(lv.back() - lv.front()),
        f_e_(1.0 / period_mm),
        df_(1.0 / (8.0 * span_)),
        f_lo_(1.0 / (o.max_period_mm > 0.0 ? o.max_period_mm : CandidateOptions{}.max_period_mm)),
        f_hi_(1.0 / min_period_mm) {}

  // The scan's local peaks with every level, in scan order: (removed, f).
  std::vector<std::pair<double, double>> scan_peaks() const {
    std::vector<std::pair<double, double>> scan, peaks;  // (f, removed); (removed, f)
    for (double f = f_lo_; f <= f_hi_; f += df_)
      if (std::abs(f - f_e_) >= 1.0 / span_) scan.emplace_back(f, removes_at(f, kNoLevel));
    for (std::size_t k = 0; k < scan.size(); ++k)
      if ((k == 0 || scan[k].second >= scan[k - 1].second) &&
          (k + 1 == scan.size() || scan[k].second >= scan[k + 1].second))
        peaks.emplace_back(scan[k].second, scan[k].first);
    return peaks;
  }

  // The period near the peaks `fs` whose cycle removes most with the level
  // `skip` left out (kNoLevel: none), and what it removes: (removed, period).
  std::pair<double, double> best_near(const std::vector<double>& fs, std::size_t skip) const {
    double d_best = 0.0, p_best = 0.0;
    for (double peak : fs) {
      for (int q = -20; q <= 20; ++q) {
        const double f = peak + q * df_ / 20.0;
        if (std::abs(f - f_e_) < 1.0 / span_ || f < f_lo_ || f > f_hi_) continue;
        const double d = removes_at(f, skip);
        if (d > d_best) {
          d_best = d;
          p_best = 1.0 / f;
        }
      }
    }
    return {d_best, p_best};
  }

  double removes_at(double f, std::size_t skip) const {
    return ip_.removes(cycle_at_levels(lv_, f, skip));
  }

 private:
  const LevelSpan::InPlace& ip_;
  const std::vector<double>& lv_;
  double span_, f_e_, df_, f_lo_, f_hi_;
};

// Whether s_j moves in lockstep with another axis on every line of the
// design: within each set, over the points measured along i, |r| ≥ 0.99
// between s_j and some other s_k. Along a body diagonal a cycle of j is a
// cycle of k at its period scaled by their slope: its kind may be told,
// not its axis.
bool moves_with_another_axis(const Problem& pb, int j, int i) {
  struct Sums {
    Eigen::Vector3d s = Eigen::Vector3d::Zero();
    Eigen::Matrix3d ss = Eigen::Matrix3d::Zero();
    double n = 0.0;
  };
  std::map<std::string, Sums> per_set;
  std::vector<bool> seen(pb.points.size(), false);
  for (const Observation& ob : pb.obs)
    if (std::abs(ob.u[i]) > 1e-9 && !seen[ob.point]) {
      seen[ob.point] = true;
      const PointContext& pc = pb.points[ob.point];
      Sums& m = per_set[pc.set];
      m.s += pc.s;
      m.ss += pc.s * pc.s.transpose();
      m.n += 1.0;
    }
  bool any = false;
  for (const auto& entry : per_set) {
    const Sums& m = entry.second;
    if (m.n < 3.0) continue;
    const Eigen::Vector3d mean = m.s / m.n;
    const Eigen::Matrix3d c = m.ss / m.n - mean * mean.transpose();
    if (!(c(j, j) > 1e-9 * (1.0 + c.trace()))) continue;  // s_j still on this line
    any = true;
    bool locked = false;
    for (int k = 0; k < 3; ++k)
      locked = locked || (k != j && c(k, k) > 0.0 && c(j, k) * c(j, k) >= 0.98 * c(j, j) * c(k, k));
    if (!locked) return false;
  }
  return any;
}

// The smooth functions of s_j on its levels lv (levels × (degree + 1)):
// 1, u, …, u^degree with u = (s_j − mid)/half over the levels' span.
Mat smooth_at_levels(const std::vector<double>& lv, int degree) {
  Mat P(static_cast<Eigen::Index>(lv.size()), degree + 1);
  const double mid = 0.5 * (lv.front() + lv.back()), half = 0.5 * (lv.back() - lv.front());
  for (std::size_t l = 0; l < lv.size(); ++l)
    for (Eigen::Index k = 0; k < P.cols(); ++k)
      P(static_cast<Eigen::Index>(l), k) = std::pow((lv[l] - mid) / half, static_cast<double>(k));
  return P;
}

}  // namespace

// The cycle period test of effect e (a cycle of axis j in direction i): the
// positions of s_j where direction i is measured, when they are levels (a
// laser line's targets, a grid's levels). A cycle there is known by its
// samples at the levels only: its period is the data's where no other period
// of the catalogue's range (away from its own main lobe, 1/span in
// frequency) removes as much in its place beside everything else of the fit
// (one column's χ² at `swap_alpha`); and it must remove most of what any
// function of the levels removes in its place (`cycle_share_of_levels`),
// else it is a piece of a structure that is not a cycle (e.g. the model's
// own table error at the levels), its period the one of many that fit best.
// Where the data tell the cycle's kind, a period another period matches
// stays its unresolved period (SelectedTerm::other_periods_mm;
// DesignAmbiguityOptions period_only_*); elsewhere its other periods become
// alternatives. `whole`: the datum and every effect fitted together.
void test_cycle_period(const Problem& pb, const Mat& D, const std::vector<Mat>& cols, std::size_t e,
                       std::vector<SelectedTerm>& effects, const DesignAmbiguityOptions& o,
                       double min_period_mm, const WholeFit* whole, std::vector<std::string>& log) {
  const Term& et = effects[e].term;
  const int j = et.axis, i = et.direction;
  std::vector<double> v;
  std::vector<bool> seen(pb.points.size(), false);
  for (const Observation& ob : pb.obs)
    if (std::abs(ob.u[i]) > 1e-9 && !seen[ob.point]) {
      seen[ob.point] = true;
      v.push_back(pb.points[ob.point].s[j]);
    }
  const std::vector<double> lv = levels_of(std::move(v), o, min_period_mm);
  SelectedTerm& st = effects[e];
  if (lv.empty()) {  // not levels: the selection's aliases are alternatives
    periods_as_alternatives(st);
    return;
  }
  const std::string levels_text =
      fmt::format("any function of {} on its {} levels", variable_name(j), lv.size());
  // Its other periods where the kind is not told either: other cycles, and
  // any function of the levels.
  auto kind_not_told = [&] {
    if (st.other_periods_mm.empty()) return;
    periods_as_alternatives(st);
    add_alternative(st, levels_text);
  };
  // The few-levels rule's: a cycle fits any values there.
  if (lv.size() <= o.few_levels) return kind_not_told();
  const SwapTest sw = swap_test(pb, D, cols, e, o.swap_alpha);
  if (!sw.valid) return kind_not_told();
  const LevelSpan levels(pb, j, lv);
  const double d_levels = levels.removes_in_place(sw.QA, sw.rA, i);
  if (sw.d_e < o.cycle_share_of_levels * d_levels) {
    kind_not_told();
    add_alternative(st, levels_text);
    if (st.separate_by.empty())
      st.separate_by = fmt::format(
          "measure {} at more positions, at irregular spacing (on its {} levels the cycle is "
          "{:.0f} % of what a function of the levels explains there)",
          axis_name(j), lv.size(), 100.0 * sw.d_e / d_levels);
    log.push_back(fmt::format(
        "design: {} (ΔRSS {:.6g}) is {:.0f} % of what any function of the {} levels of {} "
        "removes in its place (ΔRSS {:.6g})",
        et.label(), sw.d_e, 100.0 * sw.d_e / d_levels, lv.size(), variable_name(j), d_levels));
    return;
  }
  const LevelSpan::InPlace ip = levels.in_place(sw.QA, sw.rA, i);
  double margin = sw.margin;
  if (whole) {  // level_noise_margin
    // What a function of the levels removes beside the whole fit, per degree
    // of freedom (levels − 3: the datum's offset and the cycle's two columns
    // are functions of the levels already), against σ̂².
    const double k = std::max(static_cast<double>(lv.size()) - 3.0, 1.0);
    const double dof = static_cast<double>(pb.y.size() - whole->Q.cols()) - k;
    const double d_rest = levels.removes_in_place(whole->Q, whole->r, i);
    const double s2 = std::max(whole->r.squaredNorm() - d_rest, 0.0) / std::max(dof, 1.0);
    if (s2 > 0.0) margin *= std::max(1.0, d_rest / k / s2);
  }
  // Its kind is the data's where it holds nearly all of the levels'
  // structure and a smooth function of s_j (a polynomial) removes less in
  // its place by the margin: then a period another period matches is the
  // cycle's unresolved period, not another name.
  const int degree =
      std::max(std::min(o.period_only_smooth_degree, static_cast<int>(lv.size()) - 3), 1);
  const double d_smooth = ip.removes(smooth_at_levels(lv, degree));
  const bool kind_told = lv.size() >= o.period_only_min_levels &&
                         sw.d_e >= o.period_only_share * d_levels && sw.d_e - d_smooth >= margin &&
                         !moves_with_another_axis(pb, j, i);
  if (!kind_told) kind_not_told();  // the selection's aliases

  const OtherPeriods others(ip, lv, et.period_mm, o, min_period_mm);
  const std::vector<std::pair<double, double>> peaks = others.scan_peaks();
  std::vector<double> peak_fs;
  for (const auto& pk : peaks) peak_fs.push_back(pk.second);
  const auto [d_other, p_other] = others.best_near(peak_fs, kNoLevel);
  std::size_t rests_on = kNoLevel;  // the level the period rests on, if it does
  double p_alt = p_other, d_alt = d_other;
  if (!(d_other > 0.0) || !(sw.d_e - d_other < margin)) {
    if (!o.level_out_test) return;
    // Left out one level at a time: a period the other levels hold as
    // clearly (no other period within the margin there) is the data's; one
    // that another period matches once a single level is gone rests on that
    // level (on few irregular levels a pitch error with harmonics, a sum of
    // cycles, can make one cycle's best fit land on a wrong period that only
    // one level prefers). The other periods are sought near the
    // `level_out_peaks` largest peaks of the scan with every level.
    std::vector<std::pair<double, double>> by_size = peaks;
    std::sort(by_size.begin(), by_size.end(), std::greater<>());
    by_size.resize(std::min(by_size.size(), o.level_out_peaks));
    std::vector<double> largest;
    for (const auto& pk : by_size) largest.push_back(pk.second);
    for (std::size_t l = 0; l < lv.size() && rests_on == kNoLevel; ++l) {
      const double d_own = others.removes_at(1.0 / et.period_mm, l);
      const auto [d_l, p_l] = others.best_near(largest, l);
      if (d_l > 0.0 && d_own - d_l < margin) {
        rests_on = l;
        p_alt = p_l;
        d_alt = d_l;
      }
    }
    if (rests_on == kNoLevel) return;
  }
  const std::string without = rests_on == kNoLevel ? std::string()
                                                   : fmt::format(" without the level {} = {:g} mm",
                                                                 variable_name(j), lv[rests_on]);
  st.other_periods_mm.push_back(p_alt);
  if (kind_told) {
    if (st.separate_by.empty())
      st.separate_by = fmt::format(
          "measure {} at more positions, at irregular spacing (on its {} levels a cycle of {} at "
          "{:.4g} mm fits as well{})",
          axis_name(j), lv.size(), axis_name(j), p_alt, without);
    log.push_back(fmt::format(
        "design: {} (ΔRSS {:.6g}, {:.0f} % of what any function of the {} levels of {} removes; "
        "a smooth function of {} {:.6g}) is a cycle, its period not resolved: {:.4g} mm fits as "
        "well{} (ΔRSS {:.6g})",
        et.label(), sw.d_e, 100.0 * sw.d_e / d_levels, lv.size(), variable_name(j),
        variable_name(j), d_smooth, p_alt, without, d_alt));
    return;
  }
  periods_as_alternatives(st);  // the other period is then another cycle's name
  add_alternative(st, levels_text);
  if (st.separate_by.empty())
    st.separate_by =
        rests_on == kNoLevel
            ? fmt::format(
                  "measure {} at more positions, at irregular spacing (on its {} levels a cycle "
                  "of {} at {:.4g} mm fits as well)",
                  axis_name(j), lv.size(), axis_name(j), p_alt)
            : fmt::format(
                  "measure {} at more positions, at irregular spacing (the period rests on the "
                  "level {} = {:g} mm: without it a cycle of {} at {:.4g} mm fits as well)",
                  axis_name(j), variable_name(j), lv[rests_on], axis_name(j), p_alt);
  log.push_back(
      rests_on == kNoLevel
          ? fmt::format("design: {} (ΔRSS {:.6g}) is not told from a cycle at {:.4g} mm on the {} "
                        "levels of {} (ΔRSS {:.6g})",
                        et.label(), sw.d_e, p_alt, lv.size(), variable_name(j), d_alt)
          : fmt::format("design: {} (ΔRSS {:.6g}) rests on the level {} = {:g}: without it a cycle "
                        "at {:.4g} mm fits as well (ΔRSS {:.6g})",
                        et.label(), sw.d_e, variable_name(j), lv[rests_on], p_alt, d_alt));
}

}  // namespace design

void periods_as_alternatives(SelectedTerm& st) {
  for (double p : st.other_periods_mm) {
    Term other = st.term;
    other.period_mm = p;
    design::add_alternative(st, other.label());
  }
  st.other_periods_mm.clear();
}

}  // namespace abbe::diagnose
