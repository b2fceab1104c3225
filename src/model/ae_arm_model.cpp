// ae-arm: e_k = Σ_j δ_{j,k} + [ε_j × (P − M_{j,k}(q))]_k + squareness — the
// first-order vectorial model with arms from the measurement points.
#include "abbe/model/error_model.hpp"

namespace abbe::model {

Deviation ErrorModel::evaluate_ae_arm(const EvalPoint& point, const Eigen::Vector3d& s,
                                      const ModelData& data) const {
  // Scalar form: only component k of θ × arm_k is needed, so only two
  // components of each arm are formed (this runs once per path point).
  const Eigen::Vector3d sq = squareness_um(point.p);
  double ex = sq.x(), ey = sq.y(), ez = sq.z();
  const double px = point.p.x(), py = point.p.y(), pz = point.p.z();
  for (std::size_t j = 0; j < 3; ++j) {
    const AxisGeometry& g = geometry_[j];
    const AxisErrors& err = data.errors[j];
    // M_{j,k}(q) = m0_k + moves∘s; arm_k = P − M_{j,k}(q).
    const double mx = g.moves.x() * s.x(), my = g.moves.y() * s.y(), mz = g.moves.z() * s.z();
    const double tx = err.theta_urad.x(), ty = err.theta_urad.y(), tz = err.theta_urad.z();
    const double a0y = py - g.m0(1, 0) - my, a0z = pz - g.m0(2, 0) - mz;
    const double a1x = px - g.m0(0, 1) - mx, a1z = pz - g.m0(2, 1) - mz;
    const double a2x = px - g.m0(0, 2) - mx, a2y = py - g.m0(1, 2) - my;
    // µrad × mm = nm → µm.
    ex += err.delta_um.x() + 1e-3 * (ty * a0z - tz * a0y);
    ey += err.delta_um.y() + 1e-3 * (tz * a1x - tx * a1z);
    ez += err.delta_um.z() + 1e-3 * (tx * a2y - ty * a2x);
  }
  Deviation out;
  out.e_um = Eigen::Vector3d(ex, ey, ez);
  return out;
}

}  // namespace abbe::model
