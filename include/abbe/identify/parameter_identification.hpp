#pragma once
// Identification of the 12 parameters of the linear parametrisation from
// volumetric data (the dual-number paper, section 4):
//  1. the D₂ chain is expanded into monomials of the parameters
//     (ChainExpansion) — per point and component one row of the design;
//  2. the monomial coefficients are found by Moore–Penrose least squares,
//     per component (the paper: Δx, Δy, Δz separately) and jointly (all
//     components stacked, one unknown per monomial);
//  3. the 12 parameters are recovered: the linear monomials give a first
//     estimate; Gauss–Newton on the exact quadratic model (12 unknowns)
//     refines it, and its last linearisation gives the standard errors, the
//     condition number, the rank and the unidentifiable combinations.
// The known squareness is subtracted from the data first.
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "abbe/identify/chain_expansion.hpp"
#include "abbe/identify/least_squares.hpp"
#include "abbe/model/error_model.hpp"

namespace abbe::identify {

// One measured point: the nominal tip and the deviation (µm) in the
// components that were measured.
struct Observation {
  model::EvalPoint point;
  Eigen::Vector3d d_um = Eigen::Vector3d::Zero();
  std::array<bool, 3> has{true, true, true};
};

struct MonomialFit {
  std::vector<int> monomials;  // the columns: monomials with a non-zero coefficient somewhere
  LeastSquaresResult fit;      // unknowns in the order of `monomials`
};

struct ParamIdentification {
  ParamVector p = ParamVector::Zero();
  ParamVector stderr_p = ParamVector::Zero();  // NaN where not identifiable
  std::array<bool, kParamCount> identifiable{};
  LeastSquaresResult final_fit;  // the last Gauss–Newton linearisation (12 unknowns)
  int iterations = 0;
  double residual_rms_um = 0.0;
  double residual_max_um = 0.0;
  std::size_t n_points = 0, n_values = 0;
  std::array<MonomialFit, 3> per_component;  // the paper's Δx, Δy, Δz systems
  MonomialFit joint;                         // all components stacked
  // max over the products p_i·p_j of |c_ij − p̂_i·p̂_j| / max|p̂|²: how well the
  // monomial coefficients agree with the recovered parameters.
  double product_consistency = 0.0;
};

struct IdentifyOptions {
  LeastSquaresOptions least_squares;
  int max_iterations = 20;
};

ParamIdentification identify_linear(const ChainExpansion& chain,
                                    const std::vector<Observation>& data,
                                    const IdentifyOptions& options = {});

// Names of the 12 parameters, for describe_combination.
std::vector<std::string> param_names();
std::vector<std::string> monomial_names(const std::vector<int>& monomials);

}  // namespace abbe::identify
