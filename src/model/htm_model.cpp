// htm: the conventional chain of small-angle homogeneous transformations with
// the error matrices at the axis frame origins O_j(q) = Σ_{i∈U(j)} s_i·e_i
// (machine zero when every axis reads 0). Angular errors the linear readings
// already contain are counted a second time (docs/models.md).
#include "abbe/model/chain_composition.hpp"
#include "abbe/model/error_model.hpp"

namespace abbe::model {

Deviation ErrorModel::evaluate_htm(const EvalPoint& point, const Eigen::Vector3d& s,
                                   const ModelData& data) const {
  const Eigen::Vector3d d = compose_chain<double>(point.p, [&](int c, AxisMotion<double>& m) {
    std::size_t j = static_cast<std::size_t>(machine::index(order_[static_cast<std::size_t>(c)]));
    const AxisErrors& err = data.errors[j];
    m.delta = 1e-3 * err.delta_um;  // mm
    ErrorScalar<double>::rotation_minus_identity(1e-6 * err.theta_urad, m.r_minus_i);
    m.pivots.colwise() = (geometry_[j].moves * s.array()).matrix();
  });
  Deviation out;
  out.e_um = 1e3 * d + squareness_um(point.p);
  return out;
}

}  // namespace abbe::model
