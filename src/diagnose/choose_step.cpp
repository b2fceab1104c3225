#include "choose_step.hpp"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <algorithm>

#include "abbe/diagnose/separation.hpp"
#include "abbe/diagnose/statistics.hpp"
#include "parameter_scan.hpp"
#include "revisit.hpp"
#include "smooth_surplus.hpp"
#include "step.hpp"
#include "structure.hpp"
#include "time_constant.hpp"

namespace abbe::diagnose::selection {

namespace {

// A member of a combination: the candidates that take its place in the
// combination (StructureChoice::member_rivals) join its alternatives, and
// name what would separate them where its own rivals did not.
void add_rivals_in_combination(const Term& member, const std::vector<Term>& swapped_in,
                               Alternatives& amb, std::string& separation) {
  for (const Term& t : swapped_in)
    if (std::find(amb.names.begin(), amb.names.end(), t.label()) == amb.names.end())
      amb.names.push_back(t.label());
  if (separation.empty() && !swapped_in.empty())
    separation = separating_measurement(member, swapped_in, {});
}

}  // namespace

PathState::PathState(const Problem& pb, const CandidateSet& cs, const SelectionOptions& o,
                     const Mat& Q) {
  for (const Term& t : cs.fixed) {
    Cached c = cached(pb, t, Q);
    if (c.CtC.diagonal().maxCoeff() <= 0.0) continue;  // invisible in these data
    named.push_back(std::move(c));
  }
  // Smooth families: point-level Gram matrices per direction, once.
  {
    Mat R, W;
    point_sums(pb, pb.y, R, W);
    for (const Term& t : cs.generic) {
      GenericFamily g{t, {}};
      const Mat B = generic_basis(pb, t);
      for (int i = 0; i < 3; ++i)
        if (pb.direction_present[static_cast<std::size_t>(i)])
          g.G[static_cast<std::size_t>(i)] = B.transpose() * W.col(i).asDiagonal() * B;
      generic.push_back(std::move(g));
    }
  }
  const std::size_t np = pb.points.size();
  set_of.assign(np, 0);
  for (std::size_t p = 0; p < np; ++p) {
    const auto it = std::find(pb.sets.begin(), pb.sets.end(), pb.points[p].set);
    set_of[p] = it == pb.sets.end() ? 0 : static_cast<std::size_t>(it - pb.sets.begin());
  }
  tests_named = std::max(cs.named_tests, 1);
  tests_generic = std::max(cs.generic_tests, 1);
  stride = std::max<std::size_t>(1, (np + o.scan_points - 1) / o.scan_points);
  lambda = static_cast<double>(pb.obs.size()) * o.min_effect_rms * o.min_effect_rms;
  for (int j = 0; j < 3; ++j) {
    std::vector<double> v;
    v.reserve(np);
    for (const PointContext& pc : pb.points) v.push_back(pc.s[j]);
    std::sort(v.begin(), v.end());
    std::size_t levels = 0;
    for (std::size_t k = 0; k < v.size() && levels <= o.alias_levels; ++k)
      if (k == 0 || v[k] - v[k - 1] > 1e-3) ++levels;
    levelled[static_cast<std::size_t>(j)] = levels <= o.alias_levels;
  }
}

// The practical floor in units of σ̂²: an effect that removes exactly
// n·(f·σ̂)² would give ΔRSS/σ̂² ~ χ²_k(λ = n·f²) (its noise adds k and
// scatters it); the candidate must exceed that distribution's upper α
// quantile, so that its effect is shown above the floor, not only
// estimated there (min_effect_test; else ΔRSS ≥ n·f²·σ̂²).
double PathState::practical(int k, const SelectionOptions& o) {
  if (!o.min_effect_test) return lambda;
  // Cached per column count below 64 (n is fixed); a wider candidate
  // (a large smooth family) gets its own quantile.
  if (k >= static_cast<int>(practical_cache_.size()))
    return noncentral_chi2_upper_quantile(k, lambda, o.alpha);
  double& q = practical_cache_[static_cast<std::size_t>(k)];
  if (q <= 0.0) q = noncentral_chi2_upper_quantile(k, lambda, o.alpha);
  return q;
}

void PathState::advance(const Mat& Qnew, const std::vector<Term>& picked) {
  std::vector<std::string> chosen_labels;
  for (const Term& t : picked) {
    chosen_labels.push_back(t.label());
    if (t.kind == TermKind::cyclic) cycles.push_back(t);
  }
  for (Cached& c : named) {
    Mat ext(c.QtC.rows() + Qnew.cols(), c.C.cols());
    ext << c.QtC, Qnew.transpose() * c.C;
    c.QtC = std::move(ext);
  }
  // A chosen fixed candidate cannot be chosen again.
  named.erase(std::remove_if(named.begin(), named.end(),
                             [&](const Cached& c) {
                               return std::find(chosen_labels.begin(), chosen_labels.end(),
                                                c.term.label()) != chosen_labels.end();
                             }),
              named.end());
}

bool choose_step(const Problem& pb, const CandidateSet& cs, const SelectionOptions& o,
                 PathState& ps, const Mat& Q, const Vec& r, int step, StepChoice& out,
                 std::vector<std::string>& log, PathSummary* first) {
  const auto n = static_cast<Eigen::Index>(pb.obs.size());
  const double rr = r.squaredNorm();
  const double dof_base = static_cast<double>(n - Q.cols());
  std::vector<Cached> scanned;
  std::vector<Score> scores;
  const Score* best_named = nullptr;
  Mat R, W;
  point_sums(pb, r, R, W);
  // Searched families: pick the parameter by a quick projection, then
  // evaluate the best of each family exactly.
  PowerCache power_cache;
  const ScanInput scan_in{pb,
                          R,
                          W,
                          ps.set_of,
                          ps.stride,
                          o.alias_power,
                          o.refine_period,
                          o.resolve_chosen_cycles ? &ps.cycles : nullptr};
  for (const ScanFamily& f : cs.scanned) {
    std::vector<double> aliases;
    const Term t = scan_parameter(f, scan_in, power_cache, aliases);
    scanned.push_back(cached(pb, t, Q, std::move(aliases)));
  }

  // Best named candidate.
  auto consider = [&](const Cached& c) {
    const double d = delta_rss(c.C, c.CtC, c.QtC, r);
    if (d <= 0.0) return;
    const int k = c.term.columns();
    const double s2 = std::max(rr - d, 1e-300) / std::max(dof_base - k, 1.0);
    const double chi2 = chi2_upper_quantile(k, o.alpha / ps.tests_named);
    scores.push_back({&c, d, s2 * std::max(chi2, ps.practical(k, o))});
  };
  for (const Cached& c : ps.named) consider(c);
  for (const Cached& c : scanned) consider(c);
  std::sort(scores.begin(), scores.end(), [](const Score& a, const Score& b) { return a.d > b.d; });
  // σ̂² of the information criterion: the least residual variance any
  // candidate leaves (a structure still in the residual does not inflate it).
  double s2_ic = rr / dof_base;
  for (const Score& s : scores)
    s2_ic =
        std::min(s2_ic, std::max(rr - s.d, 1e-300) / std::max(dof_base - s.c->term.columns(), 1.0));
  // The smooth function's fields are set once it is found (below).
  Step step_view(pb, o, cs, Q, r, scores, ps.share_cache);
  step_view.rr = rr;
  step_view.dof_base = dof_base;
  step_view.lambda = ps.lambda;
  step_view.tests_named = ps.tests_named;
  step_view.s2_ic = s2_ic;
  for (const Score& s : scores)
    if (s.d > s.thr) {
      best_named = &s;
      break;
    }
  best_named = step_view.parsimonious(best_named);

  // Best smooth function (approximate: not orthogonalised against Q, so it
  // never overstates what it explains).
  double g_best_excess = 0.0, g_best_d = 0.0;
  Term g_best;
  bool have_generic = false;
  struct SmoothFit {
    const Term* term;
    int direction;
    double d;
  };
  std::vector<SmoothFit> smooth_fits;  // every smooth function above its floors
  for (const GenericFamily& g : ps.generic) {
    const Mat B = generic_basis(pb, g.term);
    const Mat BtR = B.transpose() * R;
    for (int i = 0; i < 3; ++i) {
      if (!pb.direction_present[static_cast<std::size_t>(i)]) continue;
      const Mat& G = g.G[static_cast<std::size_t>(i)];
      const Vec b = BtR.col(i);
      Eigen::LDLT<Mat> ldlt(G);
      const double d = b.dot(ldlt.solve(b));
      const int k = g.term.columns();
      const double s2 = std::max(rr - d, 1e-300) / std::max(dof_base - k, 1.0);
      const double thr =
          s2 * std::max(chi2_upper_quantile(k, o.alpha / ps.tests_generic), ps.practical(k, o));
      if (d > thr) smooth_fits.push_back({&g.term, i, d});
      if (d > thr && d - thr > g_best_excess) {
        g_best_excess = d - thr;
        g_best_d = d;
        g_best = g.term;
        g_best.direction = i;
        have_generic = true;
      }
    }
  }

  // Before the smooth function is taken: does a named part of its
  // structure, alone or with up to two partners, explain it as well at a
  // lower cost (docs/diagnosis.md, step 3)?
  step_view.have_generic = have_generic;
  step_view.g_best = g_best;
  step_view.g_best_d = g_best_d;
  StructureChoice structure;
  explain_structure(step_view, best_named, step, structure, log);
  // Where no named part of the best smooth function's variables explains
  // it, the parts of another smooth function of the positions that finds
  // the structure as well are tried too (structure_near_share).
  if (have_generic && o.structure_near_share > 0.0 && !structure.lead_explains &&
      !structure.combination_wins) {
    for (const SmoothFit& f : smooth_fits)
      if (f.direction == g_best.direction && f.term->vars != g_best.vars &&
          std::find(f.term->vars.begin(), f.term->vars.end(), kTimeVariable) ==
              f.term->vars.end() &&
          f.d >= o.structure_near_share * g_best_d)
        step_view.structure_vars.push_back(f.term->vars);
    if (!step_view.structure_vars.empty()) {
      StructureChoice wider;
      explain_structure(step_view, best_named, step, wider, log);
      if (wider.lead_explains || wider.combination_wins)
        structure = std::move(wider);
      else
        step_view.structure_vars.clear();
    }
  }
  // The best smooth function's columns, where a rule below needs them.
  Mat smooth_columns;
  const bool unexplained_yet =
      have_generic && !structure.lead_explains && !structure.combination_wins;
  if (unexplained_yet && (o.drift_parts_by_reproduction || o.smooth_surplus_test))
    smooth_columns = term_columns(pb, g_best);
  // Where still nothing explains it, the drifts the smooth function
  // reproduces are parts of its structure too (drift_parts_by_reproduction).
  if (unexplained_yet && o.drift_parts_by_reproduction) {
    step_view.reproduced_by = &smooth_columns;
    step_view.reproduced_cache.clear();
    StructureChoice wider;
    explain_structure(step_view, best_named, step, wider, log);
    if (wider.lead_explains || wider.combination_wins) structure = std::move(wider);
    step_view.reproduced_by = nullptr;
  }
  if (structure.lead_explains || structure.combination_wins) best_named = structure.lead;
  // What the smooth function adds beside a named part of its structure:
  // where that passes none of its own floors, the part explains the
  // structure (smooth_surplus_test).
  bool surplus_below_floor = false;
  if (o.smooth_surplus_test && have_generic && !structure.lead_explains &&
      !structure.combination_wins && !(best_named && best_named->d >= o.name_ratio * g_best_d)) {
    const auto smooth_floor = [&](int k, double s2) {
      return s2 * std::max(chi2_upper_quantile(k, o.alpha / ps.tests_generic), ps.practical(k, o));
    };
    if (const Score* part =
            part_by_surplus(step_view, structure.lead, smooth_columns, smooth_floor, step, log)) {
      best_named = part;
      surplus_below_floor = true;
    }
  }
  // The chosen cycles' periods on the exact ΔRSS (after the choice, so
  // that the finer period does not give a cycle an edge over the fixed
  // candidates it competed with: on a few regular levels every period is
  // an alias, and a freer one fits the noise).
  // A chosen drift's τ likewise (exact_tau).
  if ((o.exact_period || o.exact_tau) && best_named) {
    auto refine = [&](const Score* s) {
      const TermKind kind = s->c->term.kind;
      if (kind != TermKind::cyclic && kind != TermKind::thermal_drift) return;
      // A cycle or a drift is a scanned candidate: scanned[i] of family cs.scanned[i].
      std::size_t i = 0;
      while (i < scanned.size() && &scanned[i] != s->c) ++i;
      if (i == scanned.size()) return;
      const std::vector<double>& grid = cs.scanned[i].grid;
      if (grid.size() < 2) return;
      Score& sc = scores[static_cast<std::size_t>(s - scores.data())];
      if (kind == TermKind::thermal_drift) {
        if (o.exact_tau) sc.d = refine_tau_exactly(pb, Q, r, grid, scanned[i]);
        return;
      }
      if (!o.exact_period) return;
      const double half_step = std::abs(1.0 / grid[1] - 1.0 / grid[0]);
      const FrequencyRange range = frequency_range(cs.scanned[i]);
      sc.d = refine_period_exactly(pb, Q, r, half_step, scanned[i], range, o.aliases_at_range_end);
      if (o.rivals_by_test && !ps.levelled[static_cast<std::size_t>(s->c->term.axis)])
        confirm_aliases(pb, Q, r, half_step, sc.d, step_view.rival_margin(), scanned[i], range);
    };
    refine(best_named);
    for (const Score* s : structure.partners) refine(s);
  }

  if (best_named && (!have_generic || structure.combination_wins || structure.lead_explains ||
                     surplus_below_floor || best_named->d >= o.name_ratio * g_best_d)) {
    out.pick = best_named->c->term;
    out.C = best_named->c->C;
    out.d = best_named->d;
    out.separation = step_view.rivals(*best_named, out.amb);
    if (structure.combination_wins)
      add_rivals_in_combination(out.pick, structure.member_rivals.front(), out.amb, out.separation);
    // A combination that won against a smooth function enters whole: its
    // members explain the structure together (a partner alone may be
    // below the practical floor, e.g. the squareness part of an
    // off-centre coupling), so each is kept with it, with its own rivals.
    for (std::size_t m = 0; m < structure.partners.size(); ++m) {
      const Score* s = structure.partners[m];
      Mat Cn(n, out.C.cols() + s->c->C.cols());
      Cn << out.C, s->c->C;
      out.C = std::move(Cn);
      out.partners.push_back(s->c->term);
      out.partner_amb.emplace_back();
      Alternatives& amb = out.partner_amb.back();
      std::string sep = step_view.rivals(*s, amb);
      add_rivals_in_combination(s->c->term, structure.member_rivals[m + 1], amb, sep);
      out.partner_separation.push_back(sep);
    }
    if (!structure.partners.empty()) out.d = structure.d_partners;
  } else if (have_generic) {
    out.pick = g_best;
    out.C = term_columns(pb, out.pick);
    out.d = g_best_d;
    if (best_named) {
      out.fallback = best_named->c->term;
      out.fallback_C = best_named->c->C;
      out.fallback_d = best_named->d;
    }
  } else {
    log.push_back(fmt::format("step {}: no candidate above the significance floor", step + 1));
    return false;
  }

  // The first step's near alternatives, for the revisit (revisit.hpp).
  if (first && out.pick.kind != TermKind::unexplained && out.partners.empty())
    first_step_alternatives(pb, cs, o, Q, r, scores, out.pick, out.d, first->first_alternatives,
                            first->first_cheaper_alternatives);
  return true;
}

}  // namespace abbe::diagnose::selection
