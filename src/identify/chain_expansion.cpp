#include "abbe/identify/chain_expansion.hpp"

#include "abbe/io/units.hpp"
#include "abbe/model/chain_composition.hpp"

namespace abbe::identify {

using model::Dual2;

namespace {
Eigen::Vector3d axis_positions(const model::EvalPoint& point) {
  return point.p + Eigen::Vector3d(0.0, 0.0, point.tool_length);
}
}  // namespace

int product_index(int i, int j) {
  if (i > j) std::swap(i, j);
  // Products before row i: Σ_{r<i} (12 − r) = 12 i − i(i−1)/2.
  return kParamCount + kParamCount * i - i * (i - 1) / 2 + (j - i);
}

void monomial_params(int k, int& i, int& j) {
  if (k < kParamCount) {
    i = k;
    j = -1;
    return;
  }
  for (int r = 0; r < kParamCount; ++r)
    for (int c = r; c < kParamCount; ++c)
      if (product_index(r, c) == k) {
        i = r;
        j = c;
        return;
      }
  i = j = -1;
}

std::string monomial_name(int k) {
  int i = 0, j = 0;
  monomial_params(k, i, j);
  if (j < 0) return param_name(i);
  if (i == j) return std::string(param_name(i)) + "^2";
  return std::string(param_name(i)) + "*" + param_name(j);
}

ChainExpansion::ChainExpansion(const machine::Machine& machine)
    : machine_(&machine), geometry_(machine) {}

void ChainExpansion::evaluate(const model::EvalPoint& point,
                              const std::array<model::AxisErrors, 3>& errors,
                              Eigen::Vector3d& first_um, Eigen::Vector3d& second_um) const {
  const auto& order = machine_->chain().order();
  const model::Vector3<Dual2> d =
      model::compose_chain<Dual2>(point.p, [&](int c, model::AxisMotion<Dual2>& m) {
        const machine::Axis axis = order[static_cast<std::size_t>(c)];
        const model::AxisErrors& err = errors[static_cast<std::size_t>(machine::index(axis))];
        for (int k = 0; k < 3; ++k) {
          m.delta[k] = model::ErrorScalar<Dual2>::linear(units::kMmPerUm * err.delta_um[k]);
          m.pivots.col(k) = geometry_.measurement_point(axis, k, axis_positions(point));
        }
        model::ErrorScalar<Dual2>::rotation_minus_identity(units::kRadPerUrad * err.theta_urad,
                                                           m.r_minus_i);
      });
  for (int k = 0; k < 3; ++k) {
    first_um[k] = units::kUmPerMm * d[k].e1;
    second_um[k] = units::kUmPerMm * d[k].e2;
  }
}

Eigen::Vector3d ChainExpansion::deviation_um(const model::EvalPoint& point, const ParamVector& p,
                                             Eigen::Vector3d* second_um) const {
  Eigen::Vector3d first, second;
  evaluate(point, component_errors(p, axis_positions(point)), first, second);
  if (second_um) *second_um = second;
  return first + second;
}

Eigen::Vector3d ChainExpansion::squareness_um(const Eigen::Vector3d& p) const {
  return geometry_.squareness_um(p);
}

MonomialRows ChainExpansion::monomials(const model::EvalPoint& point) const {
  const Eigen::Vector3d s = axis_positions(point);
  MonomialRows rows = MonomialRows::Zero();
  std::array<Eigen::Vector3d, kParamCount> second_unit;
  Eigen::Vector3d first, second;
  for (int i = 0; i < kParamCount; ++i) {
    evaluate(point, component_errors(ParamVector::Unit(i), s), first, second);
    rows.col(i) = first;
    second_unit[static_cast<std::size_t>(i)] = second;
    rows.col(product_index(i, i)) = second;
  }
  for (int i = 0; i < kParamCount; ++i)
    for (int j = i + 1; j < kParamCount; ++j) {
      evaluate(point, component_errors(ParamVector::Unit(i) + ParamVector::Unit(j), s), first,
               second);
      Eigen::Vector3d c = second - second_unit[static_cast<std::size_t>(i)] -
                          second_unit[static_cast<std::size_t>(j)];
      // Polarisation leaves rounding noise where the product is absent.
      const double ref = second.cwiseAbs().maxCoeff() +
                         second_unit[static_cast<std::size_t>(i)].cwiseAbs().maxCoeff() +
                         second_unit[static_cast<std::size_t>(j)].cwiseAbs().maxCoeff();
      for (int k = 0; k < 3; ++k)
        if (std::abs(c[k]) <= 1e-13 * ref) c[k] = 0.0;
      rows.col(product_index(i, j)) = c;
    }
  return rows;
}

Eigen::Matrix<double, kMonomialCount, 1> ChainExpansion::monomial_values(const ParamVector& p) {
  Eigen::Matrix<double, kMonomialCount, 1> v;
  for (int i = 0; i < kParamCount; ++i) {
    v[i] = p[i];
    for (int j = i; j < kParamCount; ++j) v[product_index(i, j)] = p[i] * p[j];
  }
  return v;
}

}  // namespace abbe::identify
