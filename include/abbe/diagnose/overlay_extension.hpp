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
//
// Domain: outside the box and time window the overlay was fitted on its
// polynomial, smooth and time terms are held at their boundary value
// (Overlay::evaluate); such evaluations are counted for a warning
// (domain_warning). An extra deviation beyond kOverlayLimitUm or not finite
// is refused: extra_um throws abbe::InputError naming the overlay file.
#include <atomic>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>

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
  bool time_dependent() const { return overlay_.time_dependent(); }
  model::ModelKind base() const { return base_.kind(); }

  Eigen::Vector3d extra_um(const model::EvalPoint& point, const model::Deviation& base,
                           const model::ModelData& data) const override;

  // The PointContext of the overlay's base model at a point (set "").
  PointContext context(const model::EvalPoint& point, const model::ModelData& data) const;

  // Evaluations so far, and those at a point outside the domain (the box;
  // the time window too when a term depends on t). Thread-safe.
  std::size_t evaluations() const { return evaluations_.load(); }
  std::size_t outside() const { return outside_.load(); }
  // One line for a warning: how many points (the evaluations divided by
  // `per_point`, when each point is evaluated that many times; 0: counted
  // as evaluations, e.g. a solver that evaluates a point a few times) lay outside
  // the domain, the domain, the largest distance beyond it and what was done
  // there; "" when none did. For an overlay without a domain: that its
  // domain is unknown and nothing is clamped.
  std::string domain_warning(std::size_t per_point = 0) const;

 private:
  Overlay overlay_;
  bool with_time_ = false;  // a term depends on t: the time window counts
  mutable std::atomic<std::size_t> evaluations_{0}, outside_{0};
  mutable std::atomic<double> box_excess_mm_{0.0}, time_excess_s_{0.0};
  std::optional<double> fixed_time_s_;
  bool needs_models_ = false;       // a model_choice term: the two models are evaluated
  model::ErrorModel base_, other_;  // plain (unextended) models of the overlay
};

// `model` extended by the overlay in the file (Overlay::load errors name it).
model::ErrorModel extend_model(const model::ErrorModel& model, const machine::Machine& machine,
                               const std::string& overlay_file,
                               std::optional<double> fixed_time_s = std::nullopt);

}  // namespace abbe::diagnose
