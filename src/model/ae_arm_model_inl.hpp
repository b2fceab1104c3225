#pragma once
// ae-arm: e_k = Σ_j δ_{j,k} + [ε_j × (P − M_{j,k}(q))]_k + squareness — the
// first-order vectorial model with arms from the measurement points
// (docs/models.md). Inline, so that ErrorModel::evaluate() runs the lookup
// and this sum as one function (it runs once per path point); the model
// table's row points to the out-of-line copy in model_table.cpp.
#include "abbe/io/units.hpp"
#include "abbe/model/error_model.hpp"

namespace abbe::model {

inline Deviation evaluate_ae_arm_inline(const ModelGeometry& geometry, const EvalPoint& point,
                                        const Eigen::Vector3d& s, const ModelData& data) {
  // Scalar form: only component k of θ × arm_k is needed, so only two
  // components of each arm are formed. With r_j = P − moves_j∘s (the part of
  // the arm that moves), arm_{j,k} = r_j − m0_{j,k}.
  Eigen::Vector3d delta = Eigen::Vector3d::Zero();  // Σ δ, µm
  double cx = 0.0, cy = 0.0, cz = 0.0;              // Σ [θ × arm]_k, µrad × mm = nm
  for (std::size_t j = 0; j < 3; ++j) {
    const ModelGeometry::AxisGeometry& g = geometry.axis(j);
    const AxisErrors& err = data.errors[j];
    const Eigen::Array3d r = point.p.array() - g.moves * s.array();
    const double tx = err.theta_urad.x(), ty = err.theta_urad.y(), tz = err.theta_urad.z();
    cx += ty * (r.z() - g.m0(2, 0)) - tz * (r.y() - g.m0(1, 0));
    cy += tz * (r.x() - g.m0(0, 1)) - tx * (r.z() - g.m0(2, 1));
    cz += tx * (r.y() - g.m0(1, 2)) - ty * (r.x() - g.m0(0, 2));
    delta += err.delta_um;
  }
  Deviation out;
  out.e_um =
      delta + units::kUmPerUradMm * Eigen::Vector3d(cx, cy, cz) + geometry.squareness_um(point.p);
  return out;
}

}  // namespace abbe::model
