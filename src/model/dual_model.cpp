// dual: the chain composed over second-order dual numbers, errors entered as
// ε-coefficients, rotations I + [θ]ε + ½[θ]²ε² about the measurement points
// M_{j,k}(q). The ε part is the ae-arm prediction, the ε² part the
// second-order correction (reported separately).
#include "abbe/io/units.hpp"
#include "abbe/model/chain_composition.hpp"
#include "model_formulas.hpp"

namespace abbe::model {

Deviation evaluate_dual(const ModelGeometry& geometry, const EvalPoint& point,
                        const Eigen::Vector3d& s, const ModelData& data) {
  const Vector3<Dual2> d = compose_chain<Dual2>(point.p, [&](int c, AxisMotion<Dual2>& m) {
    std::size_t j =
        static_cast<std::size_t>(machine::index(geometry.order()[static_cast<std::size_t>(c)]));
    const AxisErrors& err = data.errors[j];
    for (int k = 0; k < 3; ++k)
      m.delta[k] = ErrorScalar<Dual2>::linear(units::kMmPerUm * err.delta_um[k]);
    ErrorScalar<Dual2>::rotation_minus_identity(units::kRadPerUrad * err.theta_urad, m.r_minus_i);
    const ModelGeometry::AxisGeometry& g = geometry.axis(j);
    const Eigen::Vector3d moved = (g.moves * s.array()).matrix();
    m.pivots = g.m0.colwise() + moved;
  });
  Deviation out;
  for (int k = 0; k < 3; ++k) {
    out.e_um[k] = units::kUmPerMm * (d[k].e1 + d[k].e2);
    out.second_order_um[k] = units::kUmPerMm * d[k].e2;
  }
  out.e_um += geometry.squareness_um(point.p);
  return out;
}

}  // namespace abbe::model
