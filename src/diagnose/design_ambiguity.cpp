#include "abbe/diagnose/design_ambiguity.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <numeric>
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

// The share of the time's variance left within groups of points (group_of:
// each point's group, below `groups`; 1 where time does not vary).
double time_within_groups(const Problem& pb, const std::vector<std::size_t>& group_of,
                          std::size_t groups) {
  std::vector<double> t_sum(groups, 0.0), t_n(groups, 0.0);
  double t_all = 0.0;
  for (std::size_t p = 0; p < pb.points.size(); ++p) {
    t_sum[group_of[p]] += pb.points[p].t;
    t_n[group_of[p]] += 1.0;
    t_all += pb.points[p].t;
  }
  t_all /= static_cast<double>(pb.points.size());
  double t_total = 0.0, t_within = 0.0;
  for (std::size_t p = 0; p < pb.points.size(); ++p) {
    const double t = pb.points[p].t;
    t_total += (t - t_all) * (t - t_all);
    const double mean = t_sum[group_of[p]] / t_n[group_of[p]];
    t_within += (t - mean) * (t - mean);
  }
  return t_total > 0.0 ? t_within / t_total : 1.0;
}

// The share of the time's variance left within the levels of s_j: small
// where the design walks the levels in order.
double time_within_levels(const Problem& pb, int j, const std::vector<double>& lv) {
  std::vector<std::size_t> level_of(pb.points.size());
  for (std::size_t p = 0; p < pb.points.size(); ++p)
    level_of[p] = level_index(lv, pb.points[p].s[j]);
  return time_within_groups(pb, level_of, lv.size());
}

// The share of the time's variance left within bins of s_j of about equal
// counts (`bins` of them; points at one s_j stay in one bin), for an axis
// the design does not level.
double time_within_bins(const Problem& pb, int j, std::size_t bins) {
  const std::size_t n = pb.points.size();
  if (bins < 2 || n < 2 * bins) return 1.0;
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return pb.points[a].s[j] < pb.points[b].s[j]; });
  std::vector<std::size_t> bin_of(n);
  std::size_t bin = 0, count = 0;
  for (std::size_t k = 0; k < n; ++k) {
    if (count >= n / bins && pb.points[order[k]].s[j] > pb.points[order[k - 1]].s[j]) {
      ++bin;
      count = 0;
    }
    bin_of[order[k]] = bin;
    ++count;
  }
  return time_within_groups(pb, bin_of, bin + 1);
}

// A uniform drift of `direction` at time constant `tau` (0: linear in t).
Term uniform_drift(int direction, double tau) {
  Term drift;
  drift.kind = TermKind::thermal_drift;
  drift.axis = drift.direction = direction;
  drift.tau_s = tau;
  return drift;
}

// A drift in the static effect's direction at each time constant.
std::vector<std::vector<Term>> drift_stand_ins(const Term& effect,
                                               const std::vector<double>& taus) {
  std::vector<std::vector<Term>> out;
  for (double tau : taus) out.push_back({uniform_drift(effect.direction, tau)});
  return out;
}

// The drifts a static effect of s_j becomes where t follows s_j, at each
// time constant: a uniform drift in its direction for a scale or
// squareness of j; for a coupling w·j a drift ∝ s_w·t, alone or with the
// uniform drift beside it (the drift about any zero); none for the rest.
std::vector<std::vector<Term>> drifts_following(const Term& effect, int j,
                                                const std::vector<double>& taus) {
  if (effect.direction < 0) return {};
  if ((effect.kind == TermKind::scale || effect.kind == TermKind::squareness) && effect.axis == j)
    return drift_stand_ins(effect, taus);
  if (effect.kind != TermKind::coupling || (effect.axis != j && effect.with_axis != j)) return {};
  const int w = effect.axis == j ? effect.with_axis : effect.axis;
  std::vector<std::vector<Term>> out;
  for (double tau : taus) {
    const Term uniform = uniform_drift(effect.direction, tau);
    Term proportional = uniform;
    proportional.axis = proportional.with_axis = w;
    out.push_back({proportional});
    out.push_back({proportional, uniform});
  }
  return out;
}

// The static terms a drift of direction i becomes where t follows s_j, one,
// two or all together: a scale or squareness of j; for a drift ∝ s_w·t also
// of w, and the coupling w·j.
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
  // All three: a coupling about any centre ((s_w − w0)·(s_j − j0)).
  if (parts.size() == 3) out.push_back(parts);
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

// A stand-in found as good as effect e in its place: the swap test's ΔRSS
// of the effect, the stand-in's and its label.
struct StandIn {
  double d_effect = 0.0, d = 0.0;
  std::string label;
};

// The swap test of effect e against `stand_ins` (and, where `levels` is
// given, any function of those levels in its direction, `levels_text`):
// the best one, where it removes as much as the effect or less by no more
// than the margin (one column's χ² at `alpha`); none otherwise.
std::optional<StandIn> stand_in_as_good(const Problem& pb, const Mat& D,
                                        const std::vector<Mat>& cols, std::size_t e,
                                        const std::vector<SelectedTerm>& effects,
                                        const std::vector<std::vector<Term>>& stand_ins,
                                        double alpha, const LevelSpan* levels = nullptr,
                                        const std::string& levels_text = {}) {
  const SwapTest sw = swap_test(pb, D, cols, e, alpha);
  if (!sw.valid) return std::nullopt;
  StandIn best{sw.d_e, 0.0, {}};
  if (levels) {
    best.d = levels->removes_in_place(sw.QA, sw.rA, effects[e].term.direction);
    best.label = levels_text;
  }
  best_stand_in(pb, sw, stand_ins, effects, best.d, best.label);
  if (best.label.empty() || !(sw.d_e - best.d < sw.margin)) return std::nullopt;
  return best;
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
  const Mat Qd = span::orthonormal(D);
  const std::vector<double> taus = o.tau_s.empty() ? CandidateOptions{}.tau_s : o.tau_s;
  const auto levelled =
      o.levelled_axes ? levelled_axes(pb, o, min_period_mm) : std::array<std::vector<double>, 3>{};
  if (o.levelled_axes) {
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
      // An effect is a function of the levels where its columns lie (but
      // for level_share_left) in their span, and not only by their mean:
      // beside the datum too, but for level_share_left_beside_datum. A
      // drift measured long after the machine started is mostly its mean
      // over the measurement, an offset that the datum takes as well as
      // the level indicators do.
      std::vector<bool> in_span(effects.size(), false);
      for (std::size_t e = 0; e < effects.size(); ++e) {
        const double total = cols[e].squaredNorm();
        in_span[e] = total > 0.0 && total - levels.projected(cols[e]) <= o.level_share_left * total;
        if (!in_span[e] || !(o.level_share_left_beside_datum < 1.0)) continue;
        const Mat C = residual_of(Qd, cols[e]);
        const double total_d = C.squaredNorm();
        in_span[e] = total_d - levels.projected(C) <= o.level_share_left_beside_datum * total_d;
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
        const std::optional<StandIn> best =
            stand_in_as_good(pb, D, cols, e, effects, stand_ins, o.swap_alpha,
                             timed ? &levels : nullptr, levels_text);
        if (!best) continue;
        const std::string alt =
            timed ? best->label : fmt::format("thermal_drift t→{}", axis_name(et.direction));
        add_alternative(effects[e], alt);
        if (effects[e].separate_by.empty()) effects[e].separate_by = order_text;
        log.push_back(fmt::format(
            "design: {} (ΔRSS {:.6g}) is not told from {} (ΔRSS {:.6g}): time mostly follows the "
            "{} levels of {}",
            et.label(), best->d_effect, alt, best->d, lv.size(), variable_name(j)));
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

  // Time that follows an axis the design does not level (a raster's rows):
  // the swap tests of the levelled axes, without the levels' own span.
  const bool timed_data = pb.var_hi[3] > pb.var_lo[3];
  for (int j = 0; o.time_follows_unlevelled && timed_data && j < 3; ++j) {
    if (!levelled[static_cast<std::size_t>(j)].empty()) continue;
    if (!(pb.var_hi[static_cast<std::size_t>(j)] > pb.var_lo[static_cast<std::size_t>(j)]))
      continue;
    const double left = time_within_bins(pb, j, o.time_bins);
    if (left > o.time_share_left_unlevelled) continue;
    const std::string order_text = fmt::format(
        "measure the points again in another order or after a pause (in this design time "
        "follows {}: {:.0f} % of its variance is left within bins of {})",
        axis_name(j), 100.0 * left, variable_name(j));
    for (std::size_t e = 0; e < effects.size(); ++e) {
      const Term& et = effects[e].term;
      if (et.kind == TermKind::unexplained || et.direction < 0 ||
          !effects[e].ambiguous_with.empty())
        continue;
      const bool timed = depends_on_time(et);
      const std::vector<std::vector<Term>> stand_ins =
          timed ? static_stand_ins(pb, et, j) : drifts_following(et, j, taus);
      if (stand_ins.empty()) continue;
      const std::optional<StandIn> best =
          stand_in_as_good(pb, D, cols, e, effects, stand_ins, o.swap_alpha);
      if (!best) continue;
      add_alternative(effects[e], best->label);
      if (effects[e].separate_by.empty()) effects[e].separate_by = order_text;
      log.push_back(fmt::format(
          "design: {} (ΔRSS {:.6g}) is not told from {} (ΔRSS {:.6g}): time follows {} ({:.0f} % "
          "of its variance left within bins)",
          et.label(), best->d_effect, best->label, best->d, variable_name(j), 100.0 * left));
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
  if (o.reversal_jump) {
    // Beside the datum and the other named effects: a smooth `unexplained`
    // function fitted after them could take a part of the jump (a step
    // between two passes is a function of time too), after which any
    // column removes about as little.
    std::vector<bool> named(effects.size());
    for (std::size_t f = 0; f < effects.size(); ++f)
      named[f] = effects[f].term.kind != TermKind::unexplained;
    for (std::size_t rv = 0; rv < effects.size(); ++rv) {
      const Term& rt = effects[rv].term;
      if (rt.kind != TermKind::reversal || rt.axis < 0 || rt.degree < 1) continue;
      const SwapTest sw = swap_test(pb, D, cols, rv, o.swap_alpha, named);
      if (!sw.valid) continue;
      // Whose jump it is matters only where the data hold a jump beside the
      // growth (given everything else, more than the margin: elsewhere any
      // column in its place removes as much).
      const double d_growth = sw.removes(cols[rv].col(1));
      if (!(sw.d_e - d_growth >= sw.margin)) continue;
      // The same growth with another axis's jump (a plain reversal k→d's
      // only column) in place of the term's own.
      Mat C(pb.y.size(), 2);
      C.col(0) = cols[rv].col(1);
      for (int k = 0; k < 3; ++k) {
        if (k == rt.axis) continue;
        std::vector<int> directions{k};
        if (rt.direction >= 0 && rt.direction != k) directions.push_back(rt.direction);
        for (const int d : directions) {
          Term jump;
          jump.kind = TermKind::reversal;
          jump.axis = k;
          jump.direction = d;
          C.col(1) = term_columns(pb, jump).col(0);
          if (!(C.col(1).squaredNorm() > 0.0)) continue;
          const double d_j = sw.removes(C);
          if (!(sw.d_e - d_j < sw.margin)) continue;
          const std::string alt = fmt::format("{} (its jump)", jump.label());
          add_alternative(effects[rv], alt);
          if (effects[rv].separate_by.empty())
            effects[rv].separate_by = fmt::format(
                "measure the reversal of each axis on its own (a line along each axis, ISO "
                "230-2): on these points every axis reverses at once and the jump of {} is the "
                "jump of {} as much; the growth along {} is {}'s",
                rt.label(), jump.label(), variable_name(rt.axis), axis_name(rt.axis));
          log.push_back(fmt::format(
              "design: the jump of {} (ΔRSS {:.6g}) is not told from the jump of {} beside the "
              "same growth (ΔRSS {:.6g})",
              rt.label(), sw.d_e, jump.label(), d_j));
        }
      }
    }
  }
  return log;
}

}  // namespace abbe::diagnose
