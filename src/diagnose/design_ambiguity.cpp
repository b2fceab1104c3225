#include "abbe/diagnose/design_ambiguity.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "abbe/diagnose/candidates.hpp"
#include "cycle_period_test.hpp"
#include "level_span.hpp"
#include "span.hpp"
#include "swap_test.hpp"

namespace abbe::diagnose {
namespace {

using design::add_alternative;
using design::level_index;
using design::levels_of;
using design::LevelSpan;
using design::Mat;
using design::swap_test;
using design::SwapTest;
using design::Vec;
using design::WholeFit;
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
         std::find(t.vars.begin(), t.vars.end(), kTimeVariable) != t.vars.end();
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
      if (names(effects, c)) continue;  // already in the fit
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

}  // namespace

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
    design::test_cycle_period(pb, D, cols, e, effects, o, min_period_mm, whole ? &*whole : nullptr,
                              log);
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
