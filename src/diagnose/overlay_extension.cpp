#include "abbe/diagnose/overlay_extension.hpp"

#include <algorithm>

namespace abbe::diagnose {
namespace {

model::ModelKind kind_of(const Overlay& overlay) {
  // Overlay::parse accepts only the model table's names.
  return model::parse_model_kind(overlay.base_model).value_or(model::ModelKind::ae_arm);
}

}  // namespace

OverlayExtension::OverlayExtension(Overlay overlay, const machine::Machine& machine,
                                   std::optional<double> fixed_time_s)
    : overlay_(std::move(overlay)),
      fixed_time_s_(fixed_time_s),
      base_(machine, kind_of(overlay_)),
      other_(machine, model::alternative_model(kind_of(overlay_))) {
  needs_models_ = std::any_of(overlay_.terms.begin(), overlay_.terms.end(),
                              [](const Term& t) { return t.kind == TermKind::model_choice; });
}

bool OverlayExtension::time_dependent() const {
  return std::any_of(overlay_.terms.begin(), overlay_.terms.end(), [](const Term& t) {
    return t.kind == TermKind::thermal_drift ||
           (t.kind == TermKind::unexplained &&
            std::find(t.vars.begin(), t.vars.end(), 3) != t.vars.end());
  });
}

PointContext OverlayExtension::context(const model::EvalPoint& point,
                                       const model::ModelData& data) const {
  PointContext pc;
  pc.p = point.p;
  pc.s = point.p + Eigen::Vector3d(0.0, 0.0, point.tool_length);
  pc.t = fixed_time_s_ ? *fixed_time_s_ : point.time;
  for (std::size_t k = 0; k < 3; ++k) pc.dir[k] = point.dir[k];
  // The component tables are the same for every model kind: ε_j is the
  // lookup the extended model has just made.
  for (std::size_t j = 0; j < 3; ++j) pc.eps_urad[j] = data.errors[j].theta_urad;
  if (needs_models_) {
    model::ModelData a, b;  // fresh workspaces keep this const and thread-safe
    pc.model_delta_um = other_.evaluate(point, b).e_um - base_.evaluate(point, a).e_um;
  }
  return pc;
}

Eigen::Vector3d OverlayExtension::extra_um(const model::EvalPoint& point, const model::Deviation&,
                                           const model::ModelData& data) const {
  return overlay_.evaluate(context(point, data));
}

model::ErrorModel extend_model(const model::ErrorModel& model, const machine::Machine& machine,
                               const std::string& overlay_file,
                               std::optional<double> fixed_time_s) {
  return model.with_extension(
      std::make_shared<const OverlayExtension>(Overlay::load(overlay_file), machine, fixed_time_s));
}

}  // namespace abbe::diagnose
