#pragma once
// OverlayExtension: an Overlay (effects found by `abbe diagnose`) as an
// ErrorExtension, so that any ErrorModel can carry it (`--extend` of
// predict, compensate and verify). The terms are evaluated on the
// PointContext of the overlay's own base model, as when they were fitted:
// ε_j from the component tables at the point and, for a model_choice term,
// the difference of the compared model and the base model. Stateless
// (const, thread-safe).
#include <memory>

#include "abbe/diagnose/overlay.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/model/error_extension.hpp"
#include "abbe/model/error_model.hpp"

namespace abbe::diagnose {

class OverlayExtension final : public model::ErrorExtension {
 public:
  OverlayExtension(Overlay overlay, const machine::Machine& machine);

  const Overlay& overlay() const { return overlay_; }
  model::ModelKind base() const { return base_.kind(); }

  Eigen::Vector3d extra_um(const model::EvalPoint& point, const model::Deviation& base,
                           const model::ModelData& data) const override;

  // The PointContext of the overlay's base model at a point (set "").
  PointContext context(const model::EvalPoint& point, const model::ModelData& data) const;

 private:
  Overlay overlay_;
  bool needs_models_ = false;       // a model_choice term: the two models are evaluated
  model::ErrorModel base_, other_;  // plain (unextended) models of the overlay
};

// `model` extended by the overlay in the file (Overlay::load errors name it).
model::ErrorModel extend_model(const model::ErrorModel& model, const machine::Machine& machine,
                               const std::string& overlay_file);

}  // namespace abbe::diagnose
