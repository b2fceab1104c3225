#include "step.hpp"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "abbe/diagnose/separation.hpp"
#include "abbe/diagnose/statistics.hpp"
#include "path.hpp"

namespace abbe::diagnose::selection {

bool within_variables(const Term& t, const std::vector<int>& vars) {
  auto has = [&](int v) { return std::find(vars.begin(), vars.end(), v) != vars.end(); };
  switch (t.kind) {
    case TermKind::scale:
    case TermKind::squareness:
    case TermKind::cyclic:
    case TermKind::arm_offset:
      return has(t.axis);
    case TermKind::coupling:
      return has(t.axis) && has(t.with_axis);
    case TermKind::thermal_drift:
      return has(kTimeVariable) && (t.with_axis < 0 || has(t.with_axis));
    case TermKind::reversal:  // on a serpentine walk a function of the other axes' rows
      return true;
    default:
      return false;
  }
}

double share_along(const Problem& pb, const Term& t, int direction) {
  const int k = t.columns();
  Eigen::Matrix<double, 3, Eigen::Dynamic> g(3, k);
  double along = 0.0, all = 0.0;
  for (const PointContext& pc : pb.points) {
    t.basis(pc, g);
    along += g.row(direction).squaredNorm();
    all += g.squaredNorm();
  }
  return all > 0.0 ? along / all : 0.0;
}

bool has_searched_parameter(const Term& t) {
  return t.kind == TermKind::cyclic || t.kind == TermKind::thermal_drift;
}

double criterion_cost(const Term& t, double searched_cost) {
  return t.columns() + (has_searched_parameter(t) ? searched_cost : 0.0);
}

double Step::cost(const Term& t) const { return criterion_cost(t, o.searched_cost); }

double Step::ic_gain(double d, double c) const {
  return d - s2_ic * std::log(static_cast<double>(r.size())) * c;
}

Vec Step::contribution(const Cached& c) const {
  Vec beta;
  delta_rss(c.C, c.CtC, c.QtC, r, &beta);
  Vec f = c.C * beta;
  if (Q.cols() > 0) f -= Q * (c.QtC * beta);
  return f;
}

double Step::together(const std::vector<const Score*>& members) const {
  Eigen::Index k = 0;
  for (const Score* m : members) k += m->c->C.cols();
  Mat Cj(r.size(), k), QtCj(Q.cols(), k);
  Eigen::Index at = 0;
  for (const Score* m : members) {
    Cj.middleCols(at, m->c->C.cols()) = m->c->C;
    QtCj.middleCols(at, m->c->C.cols()) = m->c->QtC;
    at += m->c->C.cols();
  }
  const Mat CtCj = Cj.transpose() * Cj;
  return delta_rss(Cj, CtCj, QtCj, r);
}

bool Step::in_structure(const Score& sc) const {
  if (!have_generic) return false;
  bool within = within_variables(sc.c->term, g_best.vars);
  for (const std::vector<int>& vars : structure_vars)
    within = within || within_variables(sc.c->term, vars);
  if (!within && !reproduced_by) return false;
  if (share_along_best(sc) < 0.5) return false;
  if (within) return true;
  // A drift, where the structure is sought by reproduction.
  if (sc.c->term.kind != TermKind::thermal_drift) return false;
  const std::string key = sc.c->term.label();
  const auto known = reproduced_cache.find(key);
  if (known != reproduced_cache.end()) return known->second;
  const bool part = !drift_nearly_static(pb, sc.c->term) && reproduces(*reproduced_by, sc);
  reproduced_cache.emplace(key, part);
  return part;
}

double Step::share_along_best(const Score& sc) const {
  // Its share along each direction, once per candidate (by label).
  const std::string key = sc.c->term.label();
  auto it = share_cache.find(key);
  if (it == share_cache.end()) {
    std::array<double, 3> sh{};
    for (int i = 0; i < 3; ++i) sh[static_cast<std::size_t>(i)] = share_along(pb, sc.c->term, i);
    it = share_cache.emplace(key, sh).first;
  }
  return it->second[static_cast<std::size_t>(g_best.direction)];
}

bool Step::reproduces(const Mat& smooth_columns, const Score& sc) const {
  if (!(sc.d > 0.0)) return false;  // no fitted contribution
  const Vec f = contribution(*sc.c);
  return removed_by(smooth_columns, Q, f) >= kReproducedShare * f.squaredNorm();
}

bool drift_nearly_static(const Problem& pb, const Term& t) {
  if (t.kind != TermKind::thermal_drift || !(t.tau_s > 0.0) || pb.points.empty()) return false;
  // Its course in time: the catalogue's drift without its position factor.
  Term course = t;
  course.with_axis = -1;
  Eigen::Matrix<double, 3, Eigen::Dynamic> g(3, course.columns());
  double m = 0.0, m2 = 0.0;
  for (const PointContext& pc : pb.points) {
    course.basis(pc, g);
    const double v = g(course.direction, 0);
    m += v;
    m2 += v * v;
  }
  const double np = static_cast<double>(pb.points.size());
  m /= np;
  const double sd = std::sqrt(std::max(m2 / np - m * m, 0.0));
  return !(sd > kNearlyStaticCourse * m);
}

bool Step::significant(const Score& sc) const {
  const int k = sc.c->term.columns();
  const double s2 = std::max(rr - sc.d, 1e-300) / std::max(dof_base - k, 1.0);
  return sc.d > s2 * chi2_upper_quantile(k, o.alpha / tests_named);
}

const Score* Step::parsimonious(const Score* largest) const {
  const Score* best = largest;
  if (!o.parsimony_ic || !largest) return best;
  const Vec f0 = contribution(*largest->c);
  for (const Score& s : scores) {
    if (&s == largest || !(s.d > s.thr) || cost(s.c->term) >= cost(largest->c->term)) continue;
    if (!(ic_gain(s.d, cost(s.c->term)) > ic_gain(best->d, cost(best->c->term)))) continue;
    if (abs_correlation(f0, contribution(*s.c)) > o.competing_corr) best = &s;
  }
  // A drift that grows with a position whose course in time adds less
  // beside its static form (the same factor at every time: a scale or a
  // squareness) than the floor a name must pass is that static form
  // (drift_course_floor).
  const Term& bt = best->c->term;
  if (!o.drift_course_floor || bt.kind != TermKind::thermal_drift || bt.with_axis < 0) return best;
  const Term form = position_term(bt.with_axis, bt.direction);
  const auto s = std::find_if(scores.begin(), scores.end(), [&](const Score& sc) {
    const Term& t = sc.c->term;
    return t.kind == form.kind && t.axis == form.axis && t.direction == form.direction;
  });
  if (s == scores.end() || !(s->d > s->thr)) return best;
  const double d_both = together({best, &*s});
  const double s2 = std::max(rr - d_both, 1e-300) / std::max(dof_base - 2.0, 1.0);
  const double floor = s2 * std::max(chi2_upper_quantile(1, o.alpha / tests_named), lambda);
  if (!(d_both - s->d > floor)) best = &*s;
  return best;
}

double Step::rival_margin() const { return s2_ic * chi2_upper_quantile(1, o.alpha); }

std::string Step::rivals(const Score& target, Alternatives& alt) const {
  const double margin = rival_margin();
  const Vec fb = contribution(*target.c);
  std::vector<Term> rivals;
  for (const Score& s : scores) {
    if (&s == &target || s.d < 0.9 * target.d) continue;
    if (cost(s.c->term) > cost(target.c->term)) continue;
    // The same effect in a simpler form (a reversal without its growth) is
    // not another name: the information criterion chose the form.
    if (same_effect(s.c->term, target.c->term)) continue;
    if (o.rivals_by_test && target.d - s.d >= margin) continue;
    if (abs_correlation(fb, contribution(*s.c)) > o.ambiguous_corr) {
      alt.names.push_back(s.c->term.label());
      rivals.push_back(s.c->term);
    }
  }
  alt.periods_mm.insert(alt.periods_mm.end(), target.c->aliases.begin(), target.c->aliases.end());
  return separating_measurement(target.c->term, rivals, target.c->aliases);
}

}  // namespace abbe::diagnose::selection
