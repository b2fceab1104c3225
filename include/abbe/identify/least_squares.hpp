#pragma once
// Moore–Penrose least squares with the diagnostics identification needs:
// numerical rank, condition number, standard errors from the residual
// variance, and the unidentifiable combinations (the null space) — reported,
// never hidden.
//
// The columns are scaled to unit norm first (the unknowns differ by orders of
// magnitude: a parameter and a product of two); rank and condition number
// refer to the scaled problem. Of all least-squares solutions the one of
// minimum norm in the caller's unknowns is returned (Moore–Penrose). A = Q·R (Householder)
// then R = U·Σ·Vᵀ (Jacobi SVD), so tall systems stay cheap.
#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

namespace abbe::identify {

struct NullDirection {
  // Unit vector in the unknowns (original scale, normalised) along which the
  // data do not change: these combinations are not identifiable.
  Eigen::VectorXd direction;
  // The same in the column-scaled unknowns (unit sensitivity each): better
  // balanced for reading which unknowns take part.
  Eigen::VectorXd direction_scaled;
};

struct LeastSquaresResult {
  Eigen::VectorXd x;                // minimum-norm solution (scaled problem)
  Eigen::VectorXd stderr_x;         // standard errors; NaN for unknowns in the null space
  std::vector<bool> identifiable;   // unknown orthogonal to the null space
  Eigen::VectorXd singular_values;  // of the column-scaled matrix, descending
  int rank = 0;
  double condition = std::numeric_limits<double>::infinity();  // σ_max/σ_min (∞ if deficient)
  double condition_in_rank = 1.0;                              // σ_max/σ_rank
  double residual_rms = 0.0;                                   // sqrt(|r|²/m)
  double sigma = 0.0;                                          // sqrt(|r|²/(m − rank))
  long rows = 0;
  std::vector<NullDirection> null_space;
};

struct LeastSquaresOptions {
  double rank_tolerance = 1e-10;  // σ_i/σ_max below this counts as zero
};

LeastSquaresResult solve_least_squares(const Eigen::MatrixXd& a, const Eigen::VectorXd& b,
                                       const LeastSquaresOptions& options = {});

// "0.71·f1 − 0.71·g3" for a null direction, coefficients below `floor` left out.
std::string describe_combination(const Eigen::VectorXd& direction,
                                 const std::vector<std::string>& names, double floor = 0.05);

}  // namespace abbe::identify
