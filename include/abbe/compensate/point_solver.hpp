#pragma once
// PointSolver: the commanded tool tip c whose predicted position is the
// nominal one, predicted(c) = c + e(c) = n, by the fixed-point iteration
// c ← n − e(c). The error field changes by µm per metre, so the iteration
// contracts by ~1e-5 per step and two model evaluations normally reach the
// 0.01 µm target; at most `max_iterations` evaluations are made.
#include <Eigen/Core>
#include <cstddef>

#include "abbe/model/error_model.hpp"

namespace abbe::compensate {

struct SolverOptions {
  double tolerance_um = 0.01;  // |c + e(c) − n| at convergence
  int max_iterations = 5;      // model evaluations
};

struct Solution {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();  // commanded tool tip, mm
  double residual_um = 0.0;                     // |c + e(c) − n|, µm
  int iterations = 0;                           // model evaluations made
  bool converged = false;
  bool out_of_range = false;  // a table lookup left the measured range
};

class PointSolver {
 public:
  PointSolver(const model::ErrorModel& model, SolverOptions options = {});

  // `nominal.dir` selects the bidirectional tables (direction of the nominal
  // motion); the same directions are used at c. Throws what the model throws
  // (out-of-range policy `error`).
  Solution solve(const model::EvalPoint& nominal, model::ModelData& data) const;

 private:
  const model::ErrorModel* model_;
  SolverOptions options_;
};

}  // namespace abbe::compensate
