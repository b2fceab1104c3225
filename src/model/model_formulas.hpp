#pragma once
// The chain formulas of the built-in models (one file each: htm_model.cpp,
// ae_arm_model_inl.hpp, dual_model.cpp), as rows of the model table.
#include "abbe/model/error_model.hpp"

namespace abbe::model {

Deviation evaluate_htm(const ModelGeometry& geometry, const EvalPoint& point,
                       const Eigen::Vector3d& s, const ModelData& data);
Deviation evaluate_ae_arm(const ModelGeometry& geometry, const EvalPoint& point,
                          const Eigen::Vector3d& s, const ModelData& data);
Deviation evaluate_dual(const ModelGeometry& geometry, const EvalPoint& point,
                        const Eigen::Vector3d& s, const ModelData& data);

}  // namespace abbe::model
