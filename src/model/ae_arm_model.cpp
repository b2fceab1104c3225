// ae-arm: e_k = Σ_j δ_{j,k} + [ε_j × (P − M_{j,k}(q))]_k + squareness — the
// first-order vectorial model with arms from the measurement points.
#include "abbe/model/error_model.hpp"

namespace abbe::model {

Deviation ErrorModel::evaluate_ae_arm(const EvalPoint& point, const Eigen::Vector3d& s,
                                      const ModelData& data) const {
  Deviation out;
  Eigen::Vector3d e = squareness_um(point.p);
  for (std::size_t j = 0; j < 3; ++j) {
    const AxisGeometry& g = geometry_[j];
    const AxisErrors& err = data.errors[j];
    const Eigen::Vector3d moved = (g.moves * s.array()).matrix();
    const Eigen::Vector3d& t = err.theta_urad;
    // arm_k = P − M_{j,k}(q); only component k of θ × arm_k is needed.
    const Eigen::Vector3d a0 = point.p - g.m0.col(0) - moved;
    const Eigen::Vector3d a1 = point.p - g.m0.col(1) - moved;
    const Eigen::Vector3d a2 = point.p - g.m0.col(2) - moved;
    // µrad × mm = nm → µm.
    e.x() += err.delta_um.x() + 1e-3 * (t.y() * a0.z() - t.z() * a0.y());
    e.y() += err.delta_um.y() + 1e-3 * (t.z() * a1.x() - t.x() * a1.z());
    e.z() += err.delta_um.z() + 1e-3 * (t.x() * a2.y() - t.y() * a2.x());
  }
  out.e_um = e;
  return out;
}

}  // namespace abbe::model
