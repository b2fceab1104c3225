#pragma once
// ErrorExtension: extra deviation terms an ErrorModel adds to its own
// prediction (the "extended model": e.g. the effects `abbe diagnose` found,
// diagnose/overlay_extension.hpp). Attached with ErrorModel::with_extension;
// every consumer of the model (predict, compensate, verify) then sees the
// extended prediction without knowing about it. Implementations must be
// thread-safe (evaluated concurrently from const models).
#include <Eigen/Core>

#include "abbe/model/error_model.hpp"

namespace abbe::model {

class ErrorExtension {
 public:
  virtual ~ErrorExtension() = default;
  // Extra deviation of the tool tip at `point`, µm, added to `base` (the
  // model's own prediction). `data` holds the component errors the model
  // has just looked up at the point (data.errors).
  virtual Eigen::Vector3d extra_um(const EvalPoint& point, const Deviation& base,
                                   const ModelData& data) const = 0;
};

}  // namespace abbe::model
