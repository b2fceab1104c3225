#pragma once
// ContextBuilder: evaluates the base error model (and the model it is
// compared with for `model_choice`) at a point and fills the PointContext the
// effect bases need (axis positions, ε_j, model difference).
#include <string>

#include "abbe/diagnose/term.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/model/error_model.hpp"

namespace abbe::diagnose {

class ContextBuilder {
 public:
  ContextBuilder(const machine::Machine& machine, model::ModelKind base);

  model::ModelKind base() const { return base_.kind(); }
  model::ModelKind other() const { return other_.kind(); }
  // The base model's prediction (µm) is returned through `predicted_um`.
  PointContext make(const model::EvalPoint& point, const std::string& set,
                    Eigen::Vector3d& predicted_um);

 private:
  model::ErrorModel base_, other_;
  model::ModelData base_data_, other_data_;
};

}  // namespace abbe::diagnose
