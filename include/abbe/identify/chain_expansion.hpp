#pragma once
// ChainExpansion: the kinematic chain of a machine over second-order dual
// numbers D₂ (model/chain_composition.hpp, arms from the measurement points,
// as the dual model), evaluated for component errors given by the linear
// parametrisation, and expanded into monomials of the 12 parameters.
//
// With every error an ε-coefficient linear in p, the ε part of the chain is
// linear in p and the ε² part is a quadratic form in p. The coefficients are
// read off the chain itself by polarisation (exact for a quadratic form):
//   linear p_i:         ε part of the chain at p = e_i
//   square p_i²:        ε² part at p = e_i
//   product p_i·p_j:    ε²(e_i + e_j) − ε²(e_i) − ε²(e_j)   (i < j)
// so the design matrix comes from the chain, not from hand-typed formulas.
#include <Eigen/Core>
#include <array>
#include <string>

#include "abbe/identify/linear_parametrisation.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/model/error_model.hpp"

namespace abbe::identify {

// Monomial k: 0..11 the parameters, then the 78 products p_i·p_j (i ≤ j) in
// the order (0,0), (0,1), …, (0,11), (1,1), …, (11,11).
constexpr int kMonomialCount = kParamCount + kParamCount * (kParamCount + 1) / 2;
using MonomialRows = Eigen::Matrix<double, 3, kMonomialCount>;

std::string monomial_name(int k);  // "f1", "f1*g1", "a^2"
// The parameters of monomial k (j = −1 for a linear monomial).
void monomial_params(int k, int& i, int& j);
int product_index(int i, int j);  // k of p_i·p_j

class ChainExpansion {
 public:
  explicit ChainExpansion(const machine::Machine& machine);

  const machine::Machine& machine() const { return *machine_; }

  // The D₂ chain for given component errors at a point (µm): the ε part
  // (first order) and the ε² part, squareness excluded.
  void evaluate(const model::EvalPoint& point, const std::array<model::AxisErrors, 3>& errors,
                Eigen::Vector3d& first_um, Eigen::Vector3d& second_um) const;

  // The deviation (ε + ε² parts, µm) of the parametrised machine without squareness.
  Eigen::Vector3d deviation_um(const model::EvalPoint& point, const ParamVector& p,
                               Eigen::Vector3d* second_um = nullptr) const;

  // The known squareness part (µm) at the tool tip.
  Eigen::Vector3d squareness_um(const Eigen::Vector3d& p_tip) const;

  // The monomial coefficients at a point: row k = component, column = monomial,
  // so deviation_um = rows · monomial_values(p).
  MonomialRows monomials(const model::EvalPoint& point) const;

  // The values of the 90 monomials for parameters p.
  static Eigen::Matrix<double, kMonomialCount, 1> monomial_values(const ParamVector& p);

 private:
  const machine::Machine* machine_;
  model::ModelGeometry geometry_;  // measurement points M_{j,k}(q), chain order, squareness
};

}  // namespace abbe::identify
