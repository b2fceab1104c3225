#include "abbe/diagnose/diagnosis.hpp"

#include <cmath>

namespace abbe::diagnose {

Diagnosis diagnose_problem(const Problem& pb, const DiagnoseOptions& o) {
  Diagnosis d;
  d.model = pb.base_model;
  d.n_points = pb.points.size();
  d.n_observations = pb.obs.size();
  d.models = pb.models;
  d.baseline = residual_stats(pb, pb.y);
  d.baseline.model = pb.base_model;
  d.folds = o.selection.folds;
  const CandidateSet cs = build_candidates(pb, o.candidates);
  const SelectionResult sel = select_effects(pb, cs, o.selection);
  d.effects = sel.terms;
  d.datum = sel.datum;
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
  d.log = sel.log;
  return d;
}

Diagnosis diagnose(const machine::Machine& machine, const io::MeasuredData& data,
                   const DiagnoseOptions& o) {
  const Problem pb = build_problem(machine, data, o.model, o.extend);
  Diagnosis d = diagnose_problem(pb, o);
  d.machine = machine.name();
  d.measured_file = data.file;
  return d;
}

Overlay make_overlay(const Diagnosis& d, const Overlay* extend) {
  Overlay ov;
  ov.base_model = d.model;
  ov.machine = d.machine;
  if (extend) ov.terms = extend->terms;
  for (const SelectedTerm& st : d.effects) ov.terms.push_back(st.term);
  return ov;
}

}  // namespace abbe::diagnose
