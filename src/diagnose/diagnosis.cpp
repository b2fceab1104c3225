#include "abbe/diagnose/diagnosis.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "abbe/io/approach_directions.hpp"
#include "abbe/machine/campaign_uncertainty.hpp"
#include "abbe/machine/travel_check.hpp"

namespace abbe::diagnose {

namespace {

// The selection on the data without gross outliers (outliers.hpp): flagged
// after the datum alone, then against each selected model until the set of
// outliers stays the same.
struct RobustFit {
  Problem work;
  CandidateSet candidates;  // of `work`, as selected from
  SelectionResult sel;
  std::vector<std::uint32_t> drop;
  double threshold = 0.0;
};

// From the outliers `drop` (and their threshold): select, flag again
// against the selected model, until the set stays the same.
RobustFit converge(const Problem& pb, const DiagnoseOptions& o, std::vector<std::uint32_t> drop,
                   double threshold) {
  const OutlierOptions& oo = o.outliers;
  RobustFit f;
  f.drop = std::move(drop);
  f.threshold = threshold;
  for (int pass = 0;; ++pass) {
    f.work = without_points(pb, f.drop);
    f.candidates = build_candidates(f.work, o.candidates);
    f.sel = select_effects(f.work, f.candidates, o.selection);
    if (!oo.enabled || pb.obs.size() < 20 || pass + 1 >= oo.max_passes) break;
    f.threshold = std::max(oo.k * robust_sigma(f.sel.residual), oo.min_threshold_um);
    std::vector<std::uint32_t> again =
        points_beyond(pb, residual_after(pb, f.sel.datum, f.sel.terms), f.threshold);
    if (again == f.drop) break;
    f.drop = std::move(again);
  }
  return f;
}

RobustFit robust_fit(const Problem& pb, const DiagnoseOptions& o) {
  const OutlierOptions& oo = o.outliers;
  if (!oo.enabled || pb.obs.size() < 20) return converge(pb, o, {}, 0.0);
  SelectionOptions quiet = o.selection;
  quiet.on_step = nullptr;
  // A coherent group that a catalogue effect explains is structure, not
  // gross error: e.g. the points of an axis run the other way lie a whole
  // reversal off, and without them the reversal cannot be seen. Selected
  // with every point, the model then leaves fewer points beyond the
  // threshold; the flagging restarts from there and its result is kept
  // when it leaves out fewer points.
  const bool group_check = oo.group_check && oo.max_passes >= 2;
  CandidateSet candidates = build_candidates(pb, o.candidates);
  double t_all = 0.0;
  std::vector<std::uint32_t> left;
  if (group_check) {
    SelectionResult all = select_effects(pb, candidates, o.selection);
    t_all = std::max(oo.k * robust_sigma(all.residual), oo.min_threshold_um);
    left = points_beyond(pb, residual_after(pb, all.datum, all.terms), t_all);
    // Nothing beyond the threshold of the model selected with every point:
    // whatever the flagging from the datum alone left out, the selection
    // with every point would win below (it leaves out none), so it is the
    // result — without the passes that would lead there.
    if (left.empty()) return RobustFit{pb, std::move(candidates), std::move(all), {}, t_all};
  }
  CandidateSet datum_only;
  datum_only.datum = std::move(candidates.datum);
  const SelectionResult first = select_effects(pb, datum_only, quiet);
  const double threshold = std::max(oo.k * robust_sigma(first.residual), oo.min_threshold_um);
  RobustFit f = converge(pb, o, points_beyond(pb, first.residual, threshold), threshold);
  if (f.drop.empty() || !group_check || left.size() >= f.drop.size()) return f;
  RobustFit g = converge(pb, o, std::move(left), t_all);
  return g.drop.size() < f.drop.size() ? g : f;
}

}  // namespace

Diagnosis diagnose_problem(const Problem& full, const DiagnoseOptions& o) {
  Diagnosis d;
  RobustFit fit = robust_fit(full, o);
  const Problem& pb = fit.work;
  const SelectionResult& sel = fit.sel;
  d.outlier_threshold_um = fit.threshold;
  d.outlier_k = o.outliers.k;
  if (!fit.drop.empty()) {
    const Eigen::VectorXd r = residual_after(full, sel.datum, sel.terms);
    std::vector<double> worst(full.points.size(), 0.0);
    for (std::size_t k = 0; k < full.obs.size(); ++k) {
      double& w = worst[full.obs[k].point];
      if (std::abs(r[static_cast<Eigen::Index>(k)]) > std::abs(w))
        w = r[static_cast<Eigen::Index>(k)];
    }
    for (std::uint32_t p : fit.drop) {
      Outlier out;
      out.point = p;
      out.line = p < full.lines.size() ? full.lines[p] : 0;
      out.set = full.points[p].set;
      out.s = full.points[p].s;
      out.residual_um = worst[p];
      d.outliers.push_back(out);
    }
  }
  d.model = pb.base_model;
  d.n_points = pb.points.size();
  d.n_observations = pb.obs.size();
  d.models = full.models;
  d.baseline = residual_stats(pb, pb.y);
  d.baseline.model = pb.base_model;
  d.folds = o.selection.folds;
  if (!pb.points.empty()) {
    d.domain.known = true;
    for (int k = 0; k < 3; ++k) {
      d.domain.lo[k] = pb.var_lo[static_cast<std::size_t>(k)];
      d.domain.hi[k] = pb.var_hi[static_cast<std::size_t>(k)];
    }
    d.domain.t_lo = pb.var_lo[3];
    d.domain.t_hi = pb.var_hi[3];
  }
  d.effects = sel.terms;
  d.explained_together = sel.explained_together;
  for (SelectedTerm& st : d.effects) st.significant = value_significant(st.term);
  d.datum = sel.datum;
  d.log = sel.log;
  DesignAmbiguityOptions design = o.design;
  if (design.tau_s.empty()) design.tau_s = o.candidates.tau_s;
  if (!(design.max_period_mm > 0.0)) design.max_period_mm = o.candidates.max_period_mm;
  for (std::string& line :
       mark_design_ambiguities(pb, d.datum, d.effects, design, o.candidates.min_period_mm))
    d.log.push_back(std::move(line));
  for (std::string& line :
       mark_unrejected_rivals(pb, d.datum, d.effects, fit.candidates, o.selection.searched_cost,
                              o.rivals, o.selection.min_effect_rms))
    d.log.push_back(std::move(line));
  d.isotropic = isotropic_scale(d.effects);
  d.blind_spots = blind_spots(pb, design, o.candidates.min_period_mm, o.candidates.max_period_mm,
                              o.candidates.max_period_span_share);
  d.extended = residual_stats(pb, sel.residual);
  d.extended.model = pb.base_model + "+effects";
  const double np = std::max<double>(static_cast<double>(d.n_points), 1.0);
  d.holdout_rms_um = std::sqrt(std::max(sel.cv_sse, 0.0) / np);
  // The baseline is the model with the datum fitted (every measurement has
  // one): the gain is what the effects add to it, both held out.
  d.baseline_holdout_rms_um = std::sqrt(sel.datum_cv_sse / np);
  d.gain_percent = d.baseline_holdout_rms_um > 0.0
                       ? 100.0 * (1.0 - d.holdout_rms_um / d.baseline_holdout_rms_um)
                       : 0.0;
  d.noise_um = sel.sigma_um;
  const NoiseEstimate ne = estimate_noise(pb);
  d.noise_independent_um = ne.sigma_um;
  d.noise_method = ne.method;
  // On every point: a reversal spike may well have been flagged as an outlier.
  CircleCheck cc =
      fit.drop.empty()
          ? check_circles(pb, sel.residual, sel.sigma_um)
          : check_circles(full, residual_after(full, sel.datum, sel.terms), sel.sigma_um);
  d.circles = std::move(cc.circles);
  d.dynamic = std::move(cc.findings);
  return d;
}

Diagnosis diagnose(const machine::Machine& machine, const io::MeasuredData& given,
                   const DiagnoseOptions& o) {
  io::MeasuredData inferred;
  std::vector<int> axes;
  if (o.infer_directions) {
    inferred = given;
    axes = io::infer_approach_directions(inferred);
  }
  const io::MeasuredData& data = o.infer_directions ? inferred : given;
  const Problem pb = build_problem(machine, data, o.model, o.extend);
  Diagnosis d = diagnose_problem(pb, o);
  std::vector<std::uint32_t> drop;
  for (const Outlier& out : d.outliers) drop.push_back(out.point);
  std::sort(drop.begin(), drop.end());
  const bool u_given = machine::has_campaign_uncertainty(machine);
  const std::size_t draws = o.tables.draws.value_or(u_given ? kDefaultTableDraws : 0);
  // The fitted points (without the outliers), for the steps below that need them.
  std::optional<Problem> without_outliers;
  if (!drop.empty() && (draws > 0 || o.extend)) without_outliers = without_points(pb, drop);
  const Problem& fitted = without_outliers ? *without_outliers : pb;
  if (draws > 0) {
    d.tables = add_table_uncertainty(machine, data, o.model, fitted, drop, draws, o.tables.seed,
                                     d.datum, d.effects);
    // A value whose u, the tables' part with it, is not below it is no name.
    for (SelectedTerm& st : d.effects) st.significant = value_significant(st.term);
    d.isotropic = isotropic_scale(d.effects);
  }
  d.tables.available = u_given;
  if (o.extend) {
    d.extend_check =
        check_transfer(without_points(build_problem(machine, data, o.model, nullptr), drop), fitted,
                       o.extend->terms.size());
    add_overlay_warnings(*o.extend, machine.name(), model::to_string(o.model), fitted,
                         d.extend_check);
  }
  d.machine = machine.name();
  d.measured_file = data.file;
  d.directions_inferred = axes;
  machine::TravelCheck travel(machine.spec().travel);
  for (const io::MeasuredRow& row : data.rows)
    travel.add(row.p, row.tool_length_or(machine.tool_length()), row.line);
  d.outside_travel_points = travel.outside();
  d.travel_text = travel.text();
  return d;
}

Overlay make_overlay(const Diagnosis& d, const Overlay* extend) {
  Overlay ov;
  ov.base_model = d.model;
  ov.machine = d.machine;
  ov.domain = d.domain;
  if (extend) {
    ov.terms = extend->terms;
    // The earlier terms were fitted on the earlier overlay's domain: the
    // new one holds both (an earlier overlay without a domain: the data's).
    if (extend->domain.known) ov.domain = extend->domain.merged(d.domain);
  }
  for (const SelectedTerm& st : d.effects) ov.terms.push_back(st.term);
  return ov;
}

}  // namespace abbe::diagnose
