#include "abbe/diagnose/rival_check.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "abbe/diagnose/design_ambiguity.hpp"
#include "abbe/diagnose/separation.hpp"
#include "abbe/diagnose/statistics.hpp"
#include "span.hpp"

namespace abbe::diagnose {
namespace {

using Mat = Eigen::MatrixXd;
using Vec = Eigen::VectorXd;

using span::orthonormal;
using span::residual_of;

// One swap test of an effect (span::SwapBasis), the residual variance σ̂²
// the effect and the rest leave, and the margin σ̂²·χ²₁(α) by which a
// stand-in may remove less.
struct SwapTest : span::SwapBasis {
  double s2 = 0.0;
  double margin = 0.0;
};

// The swap test beside the datum D and the blocks `use` of `cols`, for the
// effect's block e; none where the effect removes nothing there, no degree
// of freedom is left, or the rest leaves the effect less than `keep_share`
// of its columns' norm² beside the datum alone.
std::optional<SwapTest> swap_test(const Problem& pb, const Mat& D, const std::vector<Mat>& cols,
                                  const std::vector<bool>& use, std::size_t e, double alpha,
                                  double keep_share) {
  SwapTest t;
  static_cast<span::SwapBasis&>(t) = span::swap_basis(pb, D, cols, use, e);
  if (keep_share > 0.0 &&
      t.Ce.squaredNorm() < keep_share * residual_of(orthonormal(D), cols[e]).squaredNorm())
    return std::nullopt;
  const auto n = static_cast<Eigen::Index>(pb.obs.size());
  const double dof = static_cast<double>(n - t.QA.cols() - cols[e].cols());
  if (!(t.d_e > 0.0) || dof < 1.0) return std::nullopt;
  t.s2 = std::max(t.rA.squaredNorm() - t.d_e, 0.0) / dof;
  t.margin = t.s2 * chi2_upper_quantile(1, alpha);
  return t;
}

// The swap test of effects e and f together (f may be e), their columns
// `pair` put in e's block for the test (`cols` is as it was after), beside
// the datum and the other named effects but the smooth functions.
std::optional<SwapTest> pair_swap_test(const Problem& pb, const Mat& D, std::vector<Mat>& cols,
                                       const std::vector<SelectedTerm>& effects, std::size_t e,
                                       std::size_t f, Mat& pair, double alpha) {
  std::vector<bool> rest(effects.size());
  for (std::size_t g = 0; g < effects.size(); ++g)
    rest[g] = g != e && g != f && effects[g].term.kind != TermKind::unexplained;
  std::swap(cols[e], pair);
  std::optional<SwapTest> t = swap_test(pb, D, cols, rest, e, alpha, 0.0);
  std::swap(cols[e], pair);
  return t;
}

bool is_proportional_drift(const Term& t) {
  return t.kind == TermKind::thermal_drift && t.with_axis >= 0;
}

// The uniform drift of a drift's direction and time constant (as the
// catalogue has it: axis = direction, no position factor).
Mat uniform_drift_of(const Problem& pb, const Term& drift) {
  Term uniform = drift;
  uniform.axis = drift.direction;
  uniform.with_axis = -1;
  return term_columns(pb, uniform);
}

// A drift in proportion to s_w about the machine's zero (columns C), with
// the uniform drift beside it: the drift about any zero
// (a·(s_w − w0)·f(t) = a·s_w·f(t) − a·w0·f(t)).
Mat with_uniform_drift(const Problem& pb, const Term& drift, const Mat& C) {
  const Mat U = uniform_drift_of(pb, drift);
  Mat out(C.rows(), C.cols() + U.cols());
  out << C, U;
  return out;
}

// The candidates that could stand in place of `effect`: the fixed ones, the
// drift families at each time constant, the cycles at the effect's period.
std::vector<Term> stand_ins(const CandidateSet& cs, const Term& effect) {
  std::vector<Term> out;
  for (const Term& t : cs.fixed) out.push_back(t);
  for (const ScanFamily& f : cs.scanned) {
    if (f.base.kind == TermKind::thermal_drift) {
      for (double tau : f.grid) {
        Term t = f.base;
        t.tau_s = tau;
        out.push_back(t);
      }
    } else if (f.base.kind == TermKind::cyclic && effect.kind == TermKind::cyclic) {
      Term t = f.base;
      t.period_mm = effect.period_mm;
      out.push_back(t);
    }
  }
  return out;
}

// The rivals' labels, a drift family (kind, axis, direction, position
// factor) that stands in at several time constants once: "thermal_drift
// t→Z (at 11 time constants, 300 s – linear in t)".
std::vector<std::string> rival_labels(const std::vector<Term>& rivals) {
  std::vector<std::string> out;
  std::vector<bool> done(rivals.size(), false);
  for (std::size_t a = 0; a < rivals.size(); ++a) {
    if (done[a]) continue;
    const Term& t = rivals[a];
    std::vector<double> taus;
    for (std::size_t b = a; b < rivals.size(); ++b) {
      const Term& u = rivals[b];
      if (t.kind != TermKind::thermal_drift || u.kind != t.kind || u.axis != t.axis ||
          u.direction != t.direction || u.with_axis != t.with_axis)
        continue;
      taus.push_back(u.tau_s);
      done[b] = true;
    }
    if (taus.size() <= 1) {
      out.push_back(t.label());
      continue;
    }
    // τ = 0 stands for linear in t, the longest.
    auto key = [](double tau) { return tau > 0.0 ? tau : 1e300; };
    std::sort(taus.begin(), taus.end(), [&](double x, double y) { return key(x) < key(y); });
    auto text = [](double tau) {
      return tau > 0.0 ? fmt::format("{:g} s", tau) : std::string("linear in t");
    };
    const std::string label = t.label();
    out.push_back(fmt::format("{} (at {} time constants, {} – {})",
                              label.substr(0, label.find(" (")), taus.size(), text(taus.front()),
                              text(taus.back())));
  }
  return out;
}

// Adds `alt` to the effect's alternatives unless it is there (false then),
// and `separate_by` where the effect has no separating measurement yet.
bool add_alternative(SelectedTerm& st, std::string alt, const std::string& separate_by) {
  if (std::find(st.ambiguous_with.begin(), st.ambiguous_with.end(), alt) != st.ambiguous_with.end())
    return false;
  st.ambiguous_with.push_back(std::move(alt));
  if (st.separate_by.empty()) st.separate_by = separate_by;
  return true;
}

// Whether an alternative of the effect is a form of `family` (a label
// without its parenthesis: "thermal_drift x·t→X", "coupling x·z→X").
bool lists_family(const SelectedTerm& st, const std::string& family) {
  return std::any_of(st.ambiguous_with.begin(), st.ambiguous_with.end(), [&](const std::string& a) {
    return a == family || a.rfind(family + " ", 0) == 0;
  });
}

// A uniform drift named beside a drift in proportion to a position is
// that drift's zero as much ((s_w − w0)·f(t) holds −w0·f(t)): the pair —
// the proportional drift with its zero free and the uniform drift — is
// swapped for a drift in proportion to a position of another direction
// with its zero free and the uniform drift moved to that direction (at its
// own τ), beside the datum and the other named effects. The other drifts
// are, with RivalOptions::zero_pair_every_direction, every catalogue one of
// another direction (a rival that needs its own zero to stand in is not
// found alone, and an effect the design's rules marked is not put to the
// rival test at all), else the proportional drift's rivals found with
// their zero free (`zero_free_rivals`: effect index, rival). Where one
// removes as much (or less by no more than the margin), the uniform
// drift's direction is not the data's: the moved drift is its
// alternative, and that drift the proportional one's (one per family, at
// its best time constant). `cols`: the effects' columns (each pair is put
// in the proportional drift's block for its test and taken out again).
void mark_uniform_drifts_as_zero(const Problem& pb, const Mat& D, std::vector<Mat>& cols,
                                 std::vector<SelectedTerm>& effects, const CandidateSet& catalogue,
                                 const std::vector<std::pair<std::size_t, Term>>& zero_free_rivals,
                                 const RivalOptions& o, std::vector<std::string>& log) {
  for (std::size_t p = 0; p < effects.size(); ++p) {
    const Term pt = effects[p].term;
    if (!is_proportional_drift(pt)) continue;
    std::vector<Term> others;
    if (o.zero_pair_every_direction) {
      for (const Term& cand : stand_ins(catalogue, pt))
        if (is_proportional_drift(cand) && cand.direction != pt.direction) others.push_back(cand);
    } else {
      for (const auto& [e, rival] : zero_free_rivals)
        if (e == p && rival.direction != pt.direction) others.push_back(rival);
    }
    if (others.empty()) continue;
    for (std::size_t u = 0; u < effects.size(); ++u) {
      SelectedTerm& su = effects[u];
      if (u == p || su.term.kind != TermKind::thermal_drift || su.term.with_axis >= 0 ||
          su.term.direction != pt.direction)
        continue;
      const Mat P = with_uniform_drift(pb, pt, cols[p]);
      Mat pair(P.rows(), P.cols() + cols[u].cols());
      pair << P, cols[u];
      const std::optional<SwapTest> t = pair_swap_test(pb, D, cols, effects, p, u, pair, o.alpha);
      if (!t) continue;
      // The best time constant of each family that stands in: the drift,
      // the uniform drift moved to its direction, what the two remove.
      struct StandIn {
        Term drift, moved;
        double d = 0.0;
      };
      std::vector<StandIn> best;
      for (const Term& other : others) {
        Term moved = su.term;
        moved.axis = moved.direction = other.direction;
        const Mat R = with_uniform_drift(pb, other, term_columns(pb, other));
        const Mat M = term_columns(pb, moved);
        if (!(R.squaredNorm() > 0.0) || !(M.squaredNorm() > 0.0)) continue;
        Mat C(R.rows(), R.cols() + M.cols());
        C << R, M;
        const double d_c = t->removes(C);
        if (d_c < t->d_e - t->margin) continue;
        const auto it = std::find_if(best.begin(), best.end(),
                                     [&](const StandIn& b) { return same_effect(b.drift, other); });
        if (it == best.end())
          best.push_back({other, moved, d_c});
        else if (d_c > it->d)
          *it = {other, moved, d_c};
      }
      for (const StandIn& b : best) {
        const std::string alt =
            fmt::format("{} (the zero of {})", b.moved.label(), b.drift.label());
        const std::string text = fmt::format(
            "measure along {} on its own (an ISO 230-2 line): on these points a drift in "
            "proportion to the position fits alike in {} and {}, and its zero, a uniform "
            "drift, takes the direction of whichever is chosen",
            axis_name(b.drift.direction), axis_name(pt.direction), axis_name(b.drift.direction));
        if (!add_alternative(su, alt, text)) continue;
        // The proportional drift's own alternative, where no form of that
        // family is one yet.
        SelectedTerm& sp = effects[p];
        const std::string label = b.drift.label();
        if (!lists_family(sp, label.substr(0, label.find(" ("))))
          add_alternative(sp, label + " (with its zero, " + b.moved.label() + ")", text);
        log.push_back(fmt::format(
            "data: {} beside {} (ΔRSS {:.6g}) is not preferred over {} beside {}, each with "
            "its zero free (ΔRSS {:.6g}, margin {:.3g})",
            su.term.label(), pt.label(), t->d_e, b.moved.label(), b.drift.label(), b.d, t->margin));
      }
    }
  }
}

// A coupling's columns with its centre free: the catalogue's coupling about
// the travel centre and its linear parts beside it, d ∝ s_i and d ∝ s_j (a
// scale or a squareness each): a·(s_i − c_i)(s_j − c_j) about any centre c.
Mat with_linear_parts(const Problem& pb, const Term& coupling, const Mat& C) {
  const Mat Li = term_columns(pb, position_term(coupling.axis, coupling.direction));
  const Mat Lj = term_columns(pb, position_term(coupling.with_axis, coupling.direction));
  Mat out(C.rows(), C.cols() + Li.cols() + Lj.cols());
  out << C, Li, Lj;
  return out;
}

// An arm offset may be (part of) a coupling off its travel centre:
// a·(s_i − c_i)(s_j − c_j) is the catalogue's coupling about the centre plus
// a scale or squareness d ∝ s_i and d ∝ s_j, and along the body diagonals,
// where every position moves with the line's parameter, the model's
// angular table times an arm fits that sum or its linear part. The centre
// is the coupling's own unknown, as a drift's zero is. An arm offset named
// beside a coupling: the pair — the arm offset and that coupling with its
// centre free — is swapped for each catalogue coupling with its centre
// free, beside the datum and the other named effects. An arm offset named
// where no coupling is (RivalOptions::arm_offset_alone_as_coupling): it
// alone is swapped for each coupling with its centre free, which costs two
// columns more and must remove as much and ln(n)·σ̂² per extra column (the
// price of a column in the information criterion). Where one removes as
// much (or less by no more than the arm offset's margin,
// RivalOptions::arm_offset_floor_share), the arm offset is not the data's:
// that coupling off its centre is its alternative, and, where it is
// another coupling than the one named, that one's too.
void mark_arm_offsets_as_coupling_centres(const Problem& pb, const Mat& D, std::vector<Mat>& cols,
                                          std::vector<SelectedTerm>& effects,
                                          const CandidateSet& catalogue, double floor_sigmas,
                                          const RivalOptions& o, std::vector<std::string>& log) {
  if (std::none_of(effects.begin(), effects.end(),
                   [](const SelectedTerm& st) { return st.term.kind == TermKind::arm_offset; }))
    return;
  // Every catalogue coupling with its centre free, the stand-ins.
  std::vector<std::pair<Term, Mat>> couplings;
  for (const Term& t : catalogue.fixed)
    if (t.kind == TermKind::coupling) {
      Mat K = with_linear_parts(pb, t, term_columns(pb, t));
      if (K.squaredNorm() > 0.0) couplings.emplace_back(t, std::move(K));
    }
  // The couplings named (their index); none: the arm offset alone.
  std::vector<std::size_t> named_couplings;
  for (std::size_t c = 0; c < effects.size(); ++c)
    if (effects[c].term.kind == TermKind::coupling) named_couplings.push_back(c);
  const double ln_n = std::log(static_cast<double>(pb.obs.size()));
  for (std::size_t a = 0; a < effects.size(); ++a) {
    SelectedTerm& sa = effects[a];
    if (sa.term.kind != TermKind::arm_offset || !sa.ambiguous_with.empty()) continue;
    std::vector<std::size_t> partners = named_couplings;
    if (partners.empty() && o.arm_offset_alone_as_coupling) partners.push_back(a);
    for (const std::size_t c : partners) {
      const bool alone = c == a;
      Mat named = cols[a];
      if (!alone) {
        const Mat P = with_linear_parts(pb, effects[c].term, cols[c]);
        named.resize(P.rows(), cols[a].cols() + P.cols());
        named << cols[a], P;
      }
      const Eigen::Index named_cols = named.cols();
      const std::optional<SwapTest> t = pair_swap_test(pb, D, cols, effects, a, c, named, o.alpha);
      if (!t) continue;
      const double margin = std::max(t->margin, t->s2 * floor_sigmas);
      for (const auto& [k, K] : couplings) {
        const double extra = static_cast<double>(std::max<Eigen::Index>(K.cols() - named_cols, 0));
        const double d_k = t->removes(K) - extra * ln_n * t->s2;
        if (d_k < t->d_e - margin) continue;
        const std::string alt = fmt::format("{} off its travel centre (its linear parts {} and {})",
                                            k.label(), position_term(k.axis, k.direction).label(),
                                            position_term(k.with_axis, k.direction).label());
        const std::string text = fmt::format(
            "measure {} along {} at several {} apart from the other axes (lines parallel to "
            "the axes, or a grid): on these points an arm offset fits alike a coupling whose "
            "centre is not the travel's, or its linear part",
            axis_name(k.direction), variable_name(k.axis), variable_name(k.with_axis));
        if (!add_alternative(sa, alt, text)) continue;
        SelectedTerm& sc = effects[c];
        if (!alone && !same_effect(k, sc.term) && !lists_family(sc, k.label()))
          add_alternative(
              sc, k.label() + " (off its travel centre, in place of " + sa.term.label() + ")",
              text);
        log.push_back(fmt::format(
            "data: {}{}{} (ΔRSS {:.6g}) is not preferred over {} with its centre free (ΔRSS "
            "{:.6g}{}, margin {:.3g})",
            sa.term.label(), alone ? "" : " beside ",
            alone ? "" : sc.term.label() + " with its centre free", t->d_e, k.label(), d_k,
            extra > 0.0 ? fmt::format(" after {:g} columns' price", extra) : "", margin));
      }
    }
  }
}

}  // namespace

std::vector<std::string> mark_unrejected_rivals(const Problem& pb,
                                                const std::vector<SelectedTerm>& datum,
                                                std::vector<SelectedTerm>& effects,
                                                const CandidateSet& catalogue, double searched_cost,
                                                const RivalOptions& o, double min_effect_rms) {
  auto cost = [&](const Term& t) {
    const bool searched = t.kind == TermKind::cyclic || t.kind == TermKind::thermal_drift;
    return t.columns() + (searched ? searched_cost : 0.0);
  };
  std::vector<std::string> log;
  if (!o.enabled || effects.empty() || pb.obs.empty()) return log;
  const Mat D = span::datum_columns(pb, datum);
  const Mat Qd = orthonormal(D);
  std::vector<Mat> cols;
  for (const SelectedTerm& st : effects) cols.push_back(term_columns(pb, st.term));
  // An arm offset's share of the practical floor (arm_offset_floor_share),
  // in units of σ̂².
  const double arm_floor_sigmas = o.arm_offset_floor_share * static_cast<double>(pb.obs.size()) *
                                  min_effect_rms * min_effect_rms;
  // The rivals of a drift in proportion to a position found with their
  // zero free: the effect's index and the rival.
  std::vector<std::pair<std::size_t, Term>> zero_free_rivals;

  for (std::size_t e = 0; e < effects.size(); ++e) {
    SelectedTerm& se = effects[e];
    if (se.term.kind == TermKind::unexplained || !se.ambiguous_with.empty()) continue;
    // Everything else of the named fit: the datum and the other named
    // effects (a smooth `unexplained` function is fitted after them, on what
    // they leave — selection.hpp — and would take the effect's own shape).
    std::vector<bool> rest(effects.size()), rest_smooth(effects.size());
    bool have_smooth = false;
    for (std::size_t f = 0; f < effects.size(); ++f) {
      rest[f] = f != e && effects[f].term.kind != TermKind::unexplained;
      rest_smooth[f] = f != e;
      have_smooth = have_smooth || rest_smooth[f] != rest[f];
    }
    const std::optional<SwapTest> named_only = swap_test(pb, D, cols, rest, e, o.alpha, 0.0);
    if (!named_only) continue;
    // And beside the smooth functions too, where they leave the effect its
    // shape (RivalOptions::beside_smooth).
    const std::optional<SwapTest> with_smooth =
        o.beside_smooth && have_smooth
            ? swap_test(pb, D, cols, rest_smooth, e, o.alpha, o.smooth_keep_share)
            : std::nullopt;
    // The effect's fitted contribution after the datum, for the prefilter.
    Vec fe =
        residual_of(Qd, cols[e]) *
        Eigen::Map<const Vec>(se.term.coef.data(), static_cast<Eigen::Index>(se.term.coef.size()));
    if (se.term.coef.size() != static_cast<std::size_t>(cols[e].cols()) || !(fe.norm() > 0.0))
      fe = residual_of(Qd, named_only->Ce.col(0));
    // A drift in proportion to a position, with its zero free
    // (zero_free_drifts): its shape beyond its uniform drift, for the
    // prefilter, and what it removes with that drift in each test.
    const bool zero_free = o.zero_free_drifts && is_proportional_drift(se.term);
    Vec shape_zero_free;
    std::array<double, 2> d_zero_free{0.0, 0.0};
    if (zero_free) {
      // fe is beside the datum already: only the uniform drift's own part
      // beside it is taken out.
      shape_zero_free =
          residual_of(orthonormal(residual_of(Qd, uniform_drift_of(pb, se.term))), fe);
      const Mat CU = with_uniform_drift(pb, se.term, cols[e]);
      d_zero_free[0] = named_only->removes(CU);
      if (with_smooth) d_zero_free[1] = with_smooth->removes(CU);
    }
    // The margin by which a rival may remove less: one column's χ², and
    // for an arm offset the share of the practical floor
    // (RivalOptions::arm_offset_floor_share), in units of σ̂².
    const double floor_sigmas = se.term.kind == TermKind::arm_offset ? arm_floor_sigmas : 0.0;
    auto margin_of = [&](const SwapTest& t) { return std::max(t.margin, t.s2 * floor_sigmas); };
    std::vector<Term> rivals;
    for (const Term& cand : stand_ins(catalogue, se.term)) {
      // Parsimony: an alternative that costs more (columns, plus a
      // parameter found by search) and explains no more is not a rival.
      if (cost(cand) > cost(se.term)) continue;
      // The same effect at another time constant is not another name.
      if (cand.kind == se.term.kind && cand.axis == se.term.axis &&
          cand.direction == se.term.direction && cand.with_axis == se.term.with_axis)
        continue;
      if (names(effects, cand)) continue;
      const Mat Cc = term_columns(pb, cand);
      if (!(Cc.squaredNorm() > 0.0)) continue;
      // Two drifts in proportion to a position are compared zero free, the
      // candidate too with its uniform drift beside it.
      const bool both_proportional = zero_free && is_proportional_drift(cand);
      // Prefilter: how well the candidate (after the datum) fits the effect
      // (zero free: the part of the effect its uniform drift does not fit;
      // where the machine's zero lies far from the data, the contribution
      // about it is mostly that uniform drift).
      const Mat Cs = both_proportional ? with_uniform_drift(pb, cand, Cc) : Cc;
      const Mat Qc = orthonormal(residual_of(Qd, Cs));
      if (Qc.cols() == 0) continue;
      const Vec& shape = both_proportional ? shape_zero_free : fe;
      if (!(shape.norm() > 0.0)) continue;
      const double corr = (Qc.transpose() * shape).norm() / shape.norm();
      if (corr < o.prefilter_corr) continue;
      for (const std::optional<SwapTest>* test : {&named_only, &with_smooth}) {
        if (!*test) continue;
        const SwapTest& t = **test;
        const double d_c = t.removes(Cs);
        const double d_e = both_proportional ? d_zero_free[test == &named_only ? 0 : 1] : t.d_e;
        if (d_c < d_e - margin_of(t)) continue;
        rivals.push_back(cand);
        if (both_proportional) zero_free_rivals.emplace_back(e, cand);
        log.push_back(fmt::format(
            "data: {} (ΔRSS {:.6g}) is not preferred over {} in its place{}{} (ΔRSS {:.6g}, "
            "margin {:.3g})",
            se.term.label(), d_e, cand.label(),
            test == &with_smooth ? " beside the smooth functions" : "",
            both_proportional ? ", each with its zero free" : "", d_c, margin_of(t)));
        break;
      }
    }
    for (const std::string& label : rival_labels(rivals)) se.ambiguous_with.push_back(label);
    // A cycle named with its period unresolved that has a rival: its other
    // periods are alternatives too.
    if (!rivals.empty()) periods_as_alternatives(se);
    if (!rivals.empty() && se.separate_by.empty())
      se.separate_by = separating_measurement(se.term, rivals, {});
  }

  if (o.uniform_drift_as_zero && o.zero_free_drifts)
    mark_uniform_drifts_as_zero(pb, D, cols, effects, catalogue, zero_free_rivals, o, log);
  if (o.arm_offset_as_coupling_centre)
    mark_arm_offsets_as_coupling_centres(pb, D, cols, effects, catalogue, arm_floor_sigmas, o, log);
  return log;
}

}  // namespace abbe::diagnose
