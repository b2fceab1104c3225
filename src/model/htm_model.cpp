// htm: the conventional chain of small-angle homogeneous transformations with
// the error matrices at the axis frame origins O_j(q) = Σ_{i∈U(j)} s_i·e_i
// (machine zero when every axis reads 0). Angular errors the linear readings
// already contain are counted a second time (docs/models.md).
#include "abbe/io/units.hpp"
#include "abbe/model/chain_composition.hpp"
#include "model_formulas.hpp"

namespace abbe::model {

Deviation evaluate_htm(const ModelGeometry& geometry, const EvalPoint& point,
                       const Eigen::Vector3d& s, const ModelData& data) {
  const Eigen::Vector3d d = compose_chain<double>(point.p, [&](int c, AxisMotion<double>& m) {
    std::size_t j =
        static_cast<std::size_t>(machine::index(geometry.order()[static_cast<std::size_t>(c)]));
    const AxisErrors& err = data.errors[j];
    m.delta = units::kMmPerUm * err.delta_um;
    ErrorScalar<double>::rotation_minus_identity(units::kRadPerUrad * err.theta_urad, m.r_minus_i);
    m.pivots.colwise() = (geometry.axis(j).moves * s.array()).matrix();
  });
  Deviation out;
  out.e_um = units::kUmPerMm * d + geometry.squareness_um(point.p);
  return out;
}

}  // namespace abbe::model
