#include "abbe/diagnose/design_ambiguity.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "abbe/diagnose/candidates.hpp"
#include "abbe/diagnose/statistics.hpp"
#include "abbe/io/units.hpp"
#include "span.hpp"

namespace abbe::diagnose {
namespace {

using Mat = Eigen::MatrixXd;
using Vec = Eigen::VectorXd;

using span::orthonormal;
using span::residual_of;

// The deviation directions a term moves at these points (bit i: direction i).
unsigned direction_mask(const Problem& pb, const Term& t) {
  const int k = t.columns();
  Eigen::Matrix<double, 3, Eigen::Dynamic> g(3, k);
  unsigned mask = 0;
  for (const PointContext& pc : pb.points) {
    t.basis(pc, g);
    for (int i = 0; i < 3; ++i)
      if (g.row(i).squaredNorm() > 0.0) mask |= 1u << i;
    if (mask == 7u) break;
  }
  return mask;
}

// A cycle of axis j or a smooth function of s_j alone: what an aliased
// pitch error of j is selected as.
bool generic_of(const Term& t, int j) {
  if (t.kind == TermKind::cyclic) return t.axis == j;
  return t.kind == TermKind::unexplained && t.vars.size() == 1 && t.vars[0] == j;
}

bool depends_on_time(const Term& t) {
  if (t.kind == TermKind::thermal_drift) return true;
  return t.kind == TermKind::unexplained &&
         std::find(t.vars.begin(), t.vars.end(), 3) != t.vars.end();
}

// The level of position s among the levels lv (sorted).
std::size_t level_index(const std::vector<double>& lv, double s) {
  const auto l =
      static_cast<std::size_t>(std::lower_bound(lv.begin(), lv.end(), s - 1e-3) - lv.begin());
  return std::min(l, lv.size() - 1);
}

// The share of the time's variance left within the levels of s_j (1 where
// time does not vary): small where the design walks the levels in order.
double time_within_levels(const Problem& pb, int j, const std::vector<double>& lv) {
  std::vector<double> t_sum(lv.size(), 0.0), t_n(lv.size(), 0.0);
  std::vector<std::size_t> level_of(pb.points.size());
  double t_all = 0.0;
  for (std::size_t p = 0; p < pb.points.size(); ++p) {
    level_of[p] = level_index(lv, pb.points[p].s[j]);
    t_sum[level_of[p]] += pb.points[p].t;
    t_n[level_of[p]] += 1.0;
    t_all += pb.points[p].t;
  }
  t_all /= static_cast<double>(pb.points.size());
  double t_total = 0.0, t_within = 0.0;
  for (std::size_t p = 0; p < pb.points.size(); ++p) {
    const double t = pb.points[p].t;
    t_total += (t - t_all) * (t - t_all);
    const double mean = t_sum[level_of[p]] / t_n[level_of[p]];
    t_within += (t - mean) * (t - mean);
  }
  return t_total > 0.0 ? t_within / t_total : 1.0;
}

// The functions of the levels of s_j, per direction: the columns
// u_i·[level = l], without forming them (n × 3·levels). Each observation
// lies in one level, so the span is a sum of one 3-column block per level,
// and what it holds of a column is a 3 × 3 solve per level.
class LevelSpan {
 public:
  LevelSpan(const Problem& pb, int j, const std::vector<double>& lv)
      : pb_(pb), level_(pb.obs.size()), gram_(lv.size(), Eigen::Matrix3d::Zero()) {
    for (std::size_t ob = 0; ob < pb.obs.size(); ++ob) {
      level_[ob] = level_index(lv, pb.points[pb.obs[ob].point].s[j]);
      gram_[level_[ob]] += pb.obs[ob].u * pb.obs[ob].u.transpose();
    }
    for (Eigen::Matrix3d& g : gram_)
      g = g.completeOrthogonalDecomposition().pseudoInverse().eval();  // G⁺ per level
  }

  // The squared norm of the columns of C projected on the span.
  double projected(const Mat& C) const {
    double sum = 0.0;
    for (Eigen::Index c = 0; c < C.cols(); ++c) {
      std::vector<Eigen::Vector3d> g(gram_.size(), Eigen::Vector3d::Zero());
      for (std::size_t ob = 0; ob < level_.size(); ++ob)
        g[level_[ob]] += pb_.obs[ob].u * C(static_cast<Eigen::Index>(ob), c);
      for (std::size_t l = 0; l < g.size(); ++l) sum += g[l].dot(gram_[l] * g[l]);
    }
    return sum;
  }

  // What the functions of the levels in direction i (u_i·[level = l]) remove
  // of r_A when added to the orthonormal span QA (r_A ⟂ QA): bᵀ M⁺ b with
  // b = Cᵀ r_A and M = CᵀC − (QAᵀC)ᵀ(QAᵀC), each a sum over observations.
  double removes_in_place(const Mat& QA, const Vec& rA, int i) const {
    const InPlace ip = in_place(QA, rA, i);
    return ip.b.dot(ip.M.completeOrthogonalDecomposition().solve(ip.b));
  }

  // The same sums for functions of the levels given by their values V
  // (levels × k): what they remove in place, (Vᵀb)ᵀ(VᵀMV)⁺(Vᵀb), for many V
  // at the cost of one pass over the observations.
  struct InPlace {
    Vec b;
    Mat M;
    double removes(const Mat& V) const {
      const Vec bv = V.transpose() * b;
      const Mat Mv = V.transpose() * M * V;
      return bv.dot(Mv.completeOrthogonalDecomposition().solve(bv));
    }
  };
  InPlace in_place(const Mat& QA, const Vec& rA, int i) const {
    const auto m = static_cast<Eigen::Index>(gram_.size());
    InPlace ip{Vec::Zero(m), Mat()};
    Vec diag = Vec::Zero(m);
    Mat P = Mat::Zero(QA.cols(), m);
    for (std::size_t ob = 0; ob < level_.size(); ++ob) {
      const double c = pb_.obs[ob].u[i];
      if (c == 0.0) continue;
      const auto l = static_cast<Eigen::Index>(level_[ob]);
      const auto row = static_cast<Eigen::Index>(ob);
      ip.b[l] += c * rA[row];
      diag[l] += c * c;
      if (QA.cols() > 0) P.col(l) += c * QA.row(row).transpose();
    }
    ip.M = Mat(diag.asDiagonal()) - P.transpose() * P;
    return ip;
  }

 private:
  const Problem& pb_;
  std::vector<std::size_t> level_;     // per observation
  std::vector<Eigen::Matrix3d> gram_;  // per level: (Σ u uᵀ)⁺
};

// The static terms a drift of direction i becomes where t follows s_j, one
// or two together: a scale or squareness of j; for a drift ∝ s_w·t also of
// w, and the coupling w·j.
std::vector<std::vector<Term>> static_stand_ins(const Problem& pb, const Term& drift, int j) {
  std::vector<Term> parts{position_term(j, drift.direction)};
  if (drift.with_axis >= 0 && drift.with_axis != j) {
    parts.push_back(position_term(drift.with_axis, drift.direction));
    Term c;
    c.kind = TermKind::coupling;
    c.axis = std::min(j, drift.with_axis);
    c.with_axis = std::max(j, drift.with_axis);
    c.direction = drift.direction;
    c.centre = pb.travel_mid;
    c.half = pb.travel_half;
    parts.push_back(c);
  }
  std::vector<std::vector<Term>> out;
  for (std::size_t a = 0; a < parts.size(); ++a) {
    out.push_back({parts[a]});
    for (std::size_t b = a + 1; b < parts.size(); ++b) out.push_back({parts[a], parts[b]});
  }
  return out;
}

// A drift in the static effect's direction at each time constant.
std::vector<std::vector<Term>> drift_stand_ins(const Term& effect,
                                               const std::vector<double>& taus) {
  std::vector<std::vector<Term>> out;
  for (double tau : taus) {
    Term drift;
    drift.kind = TermKind::thermal_drift;
    drift.axis = drift.direction = effect.direction;
    drift.tau_s = tau;
    out.push_back({drift});
  }
  return out;
}

// A swap test of effect e: what it removes given everything else of the fit
// (the datum and the other effects), the one-column χ² margin at `alpha`,
// and what a stand-in removes in its place (span::SwapBasis).
struct SwapTest : span::SwapBasis {
  bool valid = false;
  double margin = 0.0;
};

SwapTest swap_test(const Problem& pb, const Mat& D, const std::vector<Mat>& cols, std::size_t e,
                   double alpha) {
  SwapTest sw;
  std::vector<bool> others(cols.size(), true);
  others[e] = false;
  static_cast<span::SwapBasis&>(sw) = span::swap_basis(pb, D, cols, others, e);
  if (sw.rank == 0) return sw;
  const double dof = static_cast<double>(pb.y.size() - sw.QA.cols() - sw.rank);
  const double s2 = std::max(sw.rA.squaredNorm() - sw.d_e, 0.0) / std::max(dof, 1.0);
  sw.margin = s2 * chi2_upper_quantile(1, alpha);
  sw.valid = true;
  return sw;
}

// The stand-in (its terms not already in the fit) that removes most in the
// effect's place, if it removes more than `d_best`: updates `d_best` and
// `best` (its label, the terms joined by " + ").
void best_stand_in(const Problem& pb, const SwapTest& sw,
                   const std::vector<std::vector<Term>>& stand_ins,
                   const std::vector<SelectedTerm>& effects, double& d_best, std::string& best) {
  for (const std::vector<Term>& group : stand_ins) {
    std::vector<Term> fresh;
    std::string label;
    for (const Term& c : group) {
      const bool selected =
          std::any_of(effects.begin(), effects.end(),
                      [&](const SelectedTerm& other) { return other.term.label() == c.label(); });
      if (selected) continue;  // already in the fit
      fresh.push_back(c);
      label += (label.empty() ? "" : " + ") + c.label();
    }
    if (fresh.empty()) continue;
    const double d_c = sw.removes(span::columns_of(pb, fresh));
    if (d_c > d_best) {
      d_best = d_c;
      best = label;
    }
  }
}

void add_alternative(SelectedTerm& st, const std::string& alt) {
  if (std::find(st.ambiguous_with.begin(), st.ambiguous_with.end(), alt) == st.ambiguous_with.end())
    st.ambiguous_with.push_back(alt);
}

// The distinct positions among `v` when they are few (3 to max_levels) and
// at least twice the catalogue's shortest period apart; else empty.
std::vector<double> levels_of(std::vector<double> v, const DesignAmbiguityOptions& o,
                              double min_period_mm) {
  std::sort(v.begin(), v.end());
  std::vector<double> levels;
  for (double x : v) {
    if (levels.empty() || x - levels.back() > 1e-3) levels.push_back(x);
    if (levels.size() > o.max_levels) break;
  }
  if (levels.size() < 3 || levels.size() > o.max_levels) return {};
  double gap = 1e300;
  for (std::size_t l = 1; l < levels.size(); ++l) gap = std::min(gap, levels[l] - levels[l - 1]);
  return gap >= 2.0 * min_period_mm ? levels : std::vector<double>{};
}

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

// The datum and every effect fitted together: its span and residual.
struct WholeFit {
  Mat Q;
  Vec r;
};

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

}  // namespace

void periods_as_alternatives(SelectedTerm& st) {
  for (double p : st.other_periods_mm) {
    Term other = st.term;
    other.period_mm = p;
    add_alternative(st, other.label());
  }
  st.other_periods_mm.clear();
}

std::array<std::vector<double>, 3> levelled_axes(const Problem& pb, const DesignAmbiguityOptions& o,
                                                 double min_period_mm) {
  std::array<std::vector<double>, 3> out;
  for (int j = 0; j < 3; ++j) {
    std::vector<double> v;
    v.reserve(pb.points.size());
    for (const PointContext& pc : pb.points) v.push_back(pc.s[j]);
    out[static_cast<std::size_t>(j)] = levels_of(std::move(v), o, min_period_mm);
  }
  return out;
}

std::vector<std::string> mark_design_ambiguities(const Problem& pb,
                                                 const std::vector<SelectedTerm>& datum,
                                                 std::vector<SelectedTerm>& effects,
                                                 const DesignAmbiguityOptions& o,
                                                 double min_period_mm) {
  std::vector<std::string> log;
  if (effects.empty() || pb.obs.empty()) return log;
  std::vector<Mat> cols;
  std::vector<unsigned> mask;
  for (const SelectedTerm& st : effects) {
    cols.push_back(term_columns(pb, st.term));
    mask.push_back(direction_mask(pb, st.term));
  }

  const Mat D = span::datum_columns(pb, datum);
  const std::vector<double> taus = o.tau_s.empty() ? CandidateOptions{}.tau_s : o.tau_s;
  if (o.levelled_axes) {
    const auto levelled = levelled_axes(pb, o, min_period_mm);
    for (int j = 0; j < 3; ++j) {
      const std::vector<double>& lv = levelled[static_cast<std::size_t>(j)];
      if (lv.empty()) continue;
      // (With time in the data any effect may be one a drift could stand in for.)
      bool any = pb.var_hi[3] > pb.var_lo[3] || lv.size() <= o.few_levels;
      for (const SelectedTerm& st : effects)
        any = any || generic_of(st.term, j) || depends_on_time(st.term);
      if (!any) continue;
      // Every function of the level of s_j, per direction: u_i · [level = l].
      const LevelSpan levels(pb, j, lv);
      std::vector<bool> in_span(effects.size(), false);
      for (std::size_t e = 0; e < effects.size(); ++e) {
        const double total = cols[e].squaredNorm();
        in_span[e] = total > 0.0 && total - levels.projected(cols[e]) <= o.level_share_left * total;
      }
      double gap = 1e300;
      for (std::size_t l = 1; l < lv.size(); ++l) gap = std::min(gap, lv[l] - lv[l - 1]);
      const std::string levels_text =
          fmt::format("any function of {} on its {} levels", variable_name(j), lv.size());
      const std::string separate = fmt::format(
          "sample {} at irregular spacing (its {} levels, {:.4g} mm or more apart, alias every "
          "period below {:.4g} mm: a cycle of {} and these effects share one structure)",
          axis_name(j), lv.size(), gap, 2.0 * gap, axis_name(j));
      // Time itself (mostly) a function of these levels: the design walks
      // the levels in order, time and s_j go together, and a drift in time
      // is a function of s_j as much.
      const bool time_mostly_follows = time_within_levels(pb, j, lv) <= o.time_share_left;
      const std::string order_text = fmt::format(
          "measure the points again in another order or after a pause (in this design time and "
          "{} vary together: {} walks its {} levels in order)",
          axis_name(j), axis_name(j), lv.size());
      // Where time mostly follows the levels, the data decide (a swap test):
      // a static effect is ambiguous with a drift in its direction (at any
      // time constant of the grid) that removes as much in its place, and a
      // drift not already ambiguous by the design with the static terms it
      // becomes when t follows s_j (a scale or squareness of j, of its own
      // axis w for a drift ∝ s_w, or their coupling).
      for (std::size_t e = 0; time_mostly_follows && e < effects.size(); ++e) {
        const Term& et = effects[e].term;
        if (et.kind == TermKind::unexplained || et.direction < 0 ||
            !effects[e].ambiguous_with.empty())
          continue;
        const bool timed = depends_on_time(et);
        if (!timed && !in_span[e]) continue;
        const std::vector<std::vector<Term>> stand_ins =
            timed ? static_stand_ins(pb, et, j) : drift_stand_ins(et, taus);
        const SwapTest sw = swap_test(pb, D, cols, e, o.swap_alpha);
        if (!sw.valid) continue;
        double d_best = 0.0;
        std::string best;
        if (timed) {
          d_best = levels.removes_in_place(sw.QA, sw.rA, et.direction);
          best = levels_text;
        }
        best_stand_in(pb, sw, stand_ins, effects, d_best, best);
        if (best.empty() || !(sw.d_e - d_best < sw.margin)) continue;
        const std::string alt =
            timed ? best : fmt::format("thermal_drift t→{}", axis_name(et.direction));
        add_alternative(effects[e], alt);
        if (effects[e].separate_by.empty()) effects[e].separate_by = order_text;
        log.push_back(fmt::format(
            "design: {} (ΔRSS {:.6g}) is not told from {} (ΔRSS {:.6g}): time mostly follows the "
            "{} levels of {}",
            et.label(), sw.d_e, alt, d_best, lv.size(), variable_name(j)));
      }
      // On at most `few_levels` levels a cycle of j with its period, phase
      // and amplitude free fits every function of the levels (after the
      // datum's offset, L − 1 ≤ 3 values): an effect that is one is a pitch
      // error of j as much, whatever the data.
      for (std::size_t e = 0; lv.size() <= o.few_levels && e < effects.size(); ++e) {
        const Term& et = effects[e].term;
        if (!in_span[e] || generic_of(et, j) || depends_on_time(et) ||
            et.kind == TermKind::unexplained || et.direction < 0)
          continue;
        add_alternative(
            effects[e],
            fmt::format("cyclic {}→{} (a pitch error at any period the {} levels alias)",
                        axis_name(j), axis_name(et.direction), lv.size()));
        add_alternative(effects[e], levels_text);
        if (effects[e].separate_by.empty())
          effects[e].separate_by = fmt::format(
              "measure {} at more levels, at irregular spacing ({} levels: a cycle of {} fits any "
              "values on them)",
              axis_name(j), lv.size(), axis_name(j));
        log.push_back(
            fmt::format("design: {} is a function of the {} levels of {}: a cycle fits it",
                        et.label(), lv.size(), variable_name(j)));
      }
      for (std::size_t g = 0; g < effects.size(); ++g) {
        if (!in_span[g] || !generic_of(effects[g].term, j)) continue;
        for (std::size_t e = 0; e < effects.size(); ++e) {
          if (e == g || !in_span[e] || generic_of(effects[e].term, j)) continue;
          if ((mask[e] & mask[g]) == 0) continue;
          add_alternative(effects[e], effects[g].term.label());
          add_alternative(effects[e], levels_text);
          add_alternative(effects[g], effects[e].term.label());
          for (std::size_t k : {g, e})
            if (effects[k].separate_by.empty()) effects[k].separate_by = separate;
          log.push_back(fmt::format("design: {} and {} are one function of {} on {} levels",
                                    effects[e].term.label(), effects[g].term.label(),
                                    variable_name(j), lv.size()));
        }
      }
    }
  }

  // The whole fit, once for every cycle's margin (the test adds
  // alternatives only: the terms stay).
  std::optional<WholeFit> whole;
  for (std::size_t e = 0; o.cycle_period_test && e < effects.size(); ++e) {
    const Term& et = effects[e].term;
    if (et.kind != TermKind::cyclic || et.axis < 0 || et.direction < 0 || !(et.period_mm > 0.0))
      continue;
    if (o.level_noise_margin && !whole) {
      Mat Q = span::basis_of(D, cols, std::vector<bool>(cols.size(), true));
      Vec r = residual_of(Q, pb.y);
      whole = WholeFit{std::move(Q), std::move(r)};
    }
    test_cycle_period(pb, D, cols, e, effects, o, min_period_mm, whole ? &*whole : nullptr, log);
  }
  // A cycle's period is left unresolved only where the cycle period test
  // told its kind; the selection's aliases of any other cycle (no levels:
  // a toolpath's, a ballbar's, the diagonals') are alternatives.
  for (std::size_t e = 0; !o.cycle_period_test && e < effects.size(); ++e)
    periods_as_alternatives(effects[e]);

  if (o.growing_reversal) {
    for (std::size_t rv = 0; rv < effects.size(); ++rv) {
      const Term& rt = effects[rv].term;
      if (rt.kind != TermKind::reversal || rt.axis < 0) continue;
      const int j = rt.axis;
      // The reversal's growth along its travel, sign(v_j)/2 · (s_j − mid)/half:
      // the growing reversal's second column (effects/reversal.cpp).
      Term grown = rt;
      grown.degree = 1;
      grown.centre = pb.travel_mid;
      grown.half = pb.travel_half.cwiseMax(1e-9);
      const Vec growth = term_columns(pb, grown).col(1);
      for (std::size_t e = 0; e < effects.size(); ++e) {
        const Term& et = effects[e].term;
        if (e == rv || et.kind == TermKind::unexplained || et.kind == TermKind::reversal) continue;
        if ((mask[e] & mask[rv]) == 0) continue;
        // What the effect and the growth each add to everything else of the
        // fit; not shown to be more than the growth: the data do not prefer
        // it significantly (at `swap_alpha`, one column's χ²).
        const SwapTest sw = swap_test(pb, D, cols, e, o.swap_alpha);
        if (!sw.valid) continue;
        const double d_e = sw.d_e, d_g = sw.removes(growth);
        if (!(d_g > 0.0) || !(d_e - d_g < sw.margin)) continue;
        const std::string alt = fmt::format("{} growing along {}", rt.label(), variable_name(j));
        add_alternative(effects[e], alt);
        if (effects[e].separate_by.empty())
          effects[e].separate_by = fmt::format(
              "drive {} both ways over its whole travel (on these points a {} that grows along "
              "{} and {} explain the same structure)",
              axis_name(j), rt.label(), variable_name(j), et.label());
        log.push_back(fmt::format(
            "design: {} (ΔRSS {:.6g}) is not told from the growth of {} along {} (ΔRSS {:.6g})",
            et.label(), d_e, rt.label(), variable_name(j), d_g));
      }
    }
  }
  return log;
}

}  // namespace abbe::diagnose
