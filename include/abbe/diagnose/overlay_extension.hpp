#pragma once
// OverlayExtension: an Overlay (effects found by `abbe diagnose`) as an
// ErrorExtension, so that any ErrorModel can carry it (`--extend` of
// predict, compensate and verify). The terms are evaluated on the
// PointContext of the overlay's own base model, as when they were fitted:
// ε_j from the component tables at the point and, for a model_choice term,
// the difference of the compared model and the base model. Stateless
// (const, thread-safe).
//
// Time: terms that depend on t (thermal_drift, unexplained functions of t)
// were fitted on the clock of the measurement campaign. By default they are
// evaluated at the point's time (predict: the time along the program);
// `fixed_time_s` evaluates them at one campaign time instead (compensate and
// verify: the state of the machine at that time, the same for every point).
#include <memory>
#include <optional>

#include "abbe/diagnose/overlay.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/model/error_extension.hpp"
#include "abbe/model/error_model.hpp"

namespace abbe::diagnose {

class OverlayExtension final : public model::ErrorExtension {
 public:
  OverlayExtension(Overlay overlay, const machine::Machine& machine,
                   std::optional<double> fixed_time_s = std::nullopt);

  const Overlay& overlay() const { return overlay_; }
  // True if a term depends on the time t.
  bool time_dependent() const;
  model::ModelKind base() const { return base_.kind(); }

  Eigen::Vector3d extra_um(const model::EvalPoint& point, const model::Deviation& base,
                           const model::ModelData& data) const override;

  // The PointContext of the overlay's base model at a point (set "").
  PointContext context(const model::EvalPoint& point, const model::ModelData& data) const;

 private:
  Overlay overlay_;
  std::optional<double> fixed_time_s_;
  bool needs_models_ = false;       // a model_choice term: the two models are evaluated
  model::ErrorModel base_, other_;  // plain (unextended) models of the overlay
};

// `model` extended by the overlay in the file (Overlay::load errors name it).
model::ErrorModel extend_model(const model::ErrorModel& model, const machine::Machine& machine,
                               const std::string& overlay_file,
                               std::optional<double> fixed_time_s = std::nullopt);

}  // namespace abbe::diagnose
