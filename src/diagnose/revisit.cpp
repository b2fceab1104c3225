#include "revisit.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include "abbe/diagnose/statistics.hpp"
#include "path.hpp"

namespace abbe::diagnose {
namespace selection {

void first_step_alternatives(const Problem& pb, const CandidateSet& cs, const SelectionOptions& o,
                             const Mat& Q, const Vec& r, const std::vector<Score>& scores,
                             const Term& pick, double d_pick, std::vector<Term>& out,
                             std::vector<Term>& cheaper) {
  out.clear();
  cheaper.clear();
  if (o.revisit_paths <= 0) return;
  std::vector<std::pair<double, Term>> near;
  const std::string pick_label = pick.label();
  auto add = [&](const Term& t, double d) {
    if (!(d >= o.revisit_share * d_pick)) return;
    const std::string label = t.label();
    if (label == pick_label) return;
    for (const auto& a : near)
      if (a.second.label() == label) return;
    near.emplace_back(d, t);
  };
  for (const Score& s : scores)
    if (s.d > s.thr) add(s.c->term, s.d);
  // A drift's own family at its other time constants (a cycle's other
  // periods are its aliases, which the cycle's own tests judge).
  if (pick.kind == TermKind::thermal_drift)
    for (const ScanFamily& f : cs.scanned) {
      const Term& b = f.base;
      if (b.kind != pick.kind || b.axis != pick.axis || b.direction != pick.direction ||
          b.with_axis != pick.with_axis)
        continue;
      for (const double tau : f.grid) {
        if (tau == pick.tau_s) continue;
        Term t = pick;
        t.tau_s = tau;
        add(t, removed_by(term_columns(pb, t), Q, r));
      }
    }
  std::stable_sort(near.begin(), near.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  for (const auto& a : near) {
    if (static_cast<int>(out.size()) >= o.revisit_paths) break;
    out.push_back(a.second);
  }
  if (!has_searched_parameter(pick)) return;
  const double pick_cost = criterion_cost(pick, o.searched_cost);
  for (const auto& a : near) {
    if (static_cast<int>(cheaper.size()) >= o.revisit_paths) break;
    if (criterion_cost(a.second, o.searched_cost) < pick_cost) cheaper.push_back(a.second);
  }
}

}  // namespace selection

namespace {

// A drift that grows with a position, revisited in place of the kept
// path's first pick when that pick is the drift's own static form (the
// scale or squareness of the same axes).
bool drift_for_its_static_form(const Term& alt, const std::optional<Term>& first) {
  return first && alt.kind == TermKind::thermal_drift && alt.with_axis >= 0 &&
         first->label() == position_term(alt.with_axis, alt.direction).label();
}

bool ends_with_smooth_function(const SelectionResult& res) {
  return std::any_of(res.terms.begin(), res.terms.end(),
                     [](const SelectedTerm& st) { return st.term.kind == TermKind::unexplained; });
}

// The path's cost on the criterion (its effects; the datum is every path's)
// and its columns (the datum's too).
double effects_cost(const SelectionResult& res, double searched_cost) {
  double cost = 0.0;
  for (const SelectedTerm& st : res.terms)
    cost += selection::criterion_cost(st.term, searched_cost);
  return cost;
}

// The path's effects with a parameter found by search (a drift's time
// constant, a cycle's period).
int searched_effects(const SelectionResult& res) {
  return static_cast<int>(std::count_if(
      res.terms.begin(), res.terms.end(),
      [](const SelectedTerm& st) { return selection::has_searched_parameter(st.term); }));
}

double columns(const SelectionResult& res) {
  int k = 0;
  for (const SelectedTerm& st : res.datum) k += st.term.columns();
  for (const SelectedTerm& st : res.terms) k += st.term.columns();
  return static_cast<double>(k);
}

}  // namespace

SelectionResult select_effects(const Problem& pb, const CandidateSet& cs,
                               const SelectionOptions& o) {
  selection::PathSummary kept;
  SelectionResult best = selection::select_path(pb, cs, o, nullptr, kept);
  // Where the path ends with a smooth function every near alternative is
  // tried; else, with revisit_searched_first, those that cost less than a
  // first pick found by search (a static squareness beside a drift that
  // grows with z: on a design whose time follows a position, the drift can
  // take part of a second effect's structure at the first step).
  std::vector<Term> alternatives;
  const bool by_smooth_function = ends_with_smooth_function(best);
  if (by_smooth_function) {
    alternatives = kept.first_alternatives;
  } else if (o.revisit_searched_first) {
    alternatives = kept.first_cheaper_alternatives;
  }
  // The path without an arm offset picked first at all: an arm offset moves
  // the points in several directions at once, at ratios the model's angular
  // tables fix, and can take two static effects' lines (a scale of X and a
  // squareness dZ ∝ x) at its own ratio, leaving each a remainder.
  std::optional<Term> arm_first;
  if (by_smooth_function && o.revisit_paths > 0 && o.revisit_without_arm_offset && kept.first &&
      kept.first->kind == TermKind::arm_offset)
    arm_first = kept.first;
  if (alternatives.empty() && !arm_first) return best;
  SelectionOptions again = o;
  again.on_step = nullptr;  // the progress of the path that counts has been shown
  const auto n = static_cast<double>(pb.obs.size());
  auto variance = [&](const selection::PathSummary& p, const SelectionResult& res) {
    return p.rss / std::max(n - columns(res), 1.0);
  };
  // The two paths on the criterion, RSS + σ̂²·ln(n)·cost, σ̂² the smaller
  // residual variance of the two.
  struct Comparison {
    double s2, ic_path, ic_kept;
  };
  auto compare = [&](const selection::PathSummary& path, const SelectionResult& res) {
    const double s2 = std::min(variance(kept, best), variance(path, res));
    return Comparison{s2, path.rss + s2 * std::log(n) * effects_cost(res, o.searched_cost),
                      kept.rss + s2 * std::log(n) * effects_cost(best, o.searched_cost)};
  };
  // Better by more than the rounding of two fits of the same model (a path
  // whose first pick the backward check dropped may end where the kept one
  // did).
  auto lower = [](const Comparison& c) {
    return c.ic_path < c.ic_kept - 1e-6 * std::abs(c.ic_kept);
  };
  std::vector<std::string> notes;
  for (const Term& alt : alternatives) {
    selection::PathSummary path;
    SelectionResult res = selection::select_path(pb, cs, again, &alt, path);
    const Comparison c = compare(path, res);
    const bool better = lower(c) && res.cv_sse <= best.cv_sse;
    // A static first pick in place of a searched one is tried for parsimony:
    // a path that ends with more searched effects than the kept one (the
    // drift traded for drifts, each with its time constant) does not win.
    // Nor does a path that names the kept first pick after all: its
    // alternative did not take the pick's place but joined it (a cycle whose
    // period aliases a scale on a levelled axis, beside that scale).
    const int searched_path = searched_effects(res), searched_kept = searched_effects(best);
    const bool joined =
        o.revisit_alternative_replaces && kept.first && names(res.terms, *kept.first);
    // A drift that grows with a position in place of its own static form
    // (the kept first pick: drift_course_floor made it so, or it removed
    // more) must gain by its course what it must add beside that form at
    // the step: the χ² of one column and the practical floor — unless its
    // path names the structure the kept path left to a smooth function
    // (revisit_course_floor).
    const bool course_short =
        o.revisit_course_floor && drift_for_its_static_form(alt, kept.first) &&
        (!by_smooth_function || ends_with_smooth_function(res)) &&
        !(kept.rss - path.rss > c.s2 * std::max(chi2_upper_quantile(1, o.alpha),
                                                n * o.min_effect_rms * o.min_effect_rms));
    const bool wins = better && !course_short &&
                      ((by_smooth_function && !joined) || searched_path <= searched_kept);
    notes.push_back(fmt::format(
        "revisit: first step {} in place of {}: criterion {:.6g} against {:.6g}, held-out SSE "
        "{:.6g} against {:.6g}{}",
        alt.label(), kept.first ? kept.first->label() : std::string("nothing"), c.ic_path,
        c.ic_kept, res.cv_sse, best.cv_sse,
        wins           ? std::string(": taken")
        : course_short ? std::string(": not taken, its course adds less than the floor")
        : better       ? fmt::format(": not taken, {} effects with a searched parameter against {}",
                                     searched_path, searched_kept)
                       : std::string()));
    if (wins) {
      best = std::move(res);
      kept = path;
    }
  }
  if (arm_first) {
    const std::string label = arm_first->label();
    CandidateSet without = cs;
    without.fixed.erase(std::remove_if(without.fixed.begin(), without.fixed.end(),
                                       [&](const Term& t) { return t.label() == label; }),
                        without.fixed.end());
    selection::PathSummary path;
    SelectionResult res = selection::select_path(pb, without, again, nullptr, path);
    const Comparison c = compare(path, res);
    // Not a near alternative of the same step: its fitted values differ from
    // the kept path's by δ, and the held-out SSE of two fits that differ by
    // δ has a standard error of about 2·σ̂·‖δ‖; held out, it must not be
    // worse beyond that.
    const double resolution = 2.0 * std::sqrt(c.s2) * (res.residual - best.residual).norm();
    const bool wins = lower(c) && res.cv_sse <= best.cv_sse + resolution;
    notes.push_back(fmt::format(
        "revisit: without {}: criterion {:.6g} against {:.6g}, held-out SSE {:.6g} against "
        "{:.6g} (its resolution {:.3g}){}",
        label, c.ic_path, c.ic_kept, res.cv_sse, best.cv_sse, resolution, wins ? ": taken" : ""));
    if (wins) {
      best = std::move(res);
      kept = path;
    }
  }
  best.log.insert(best.log.end(), notes.begin(), notes.end());
  return best;
}

}  // namespace abbe::diagnose
