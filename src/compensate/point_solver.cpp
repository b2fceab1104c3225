#include "abbe/compensate/point_solver.hpp"

namespace abbe::compensate {

PointSolver::PointSolver(const model::ErrorModel& model, SolverOptions options)
    : model_(&model), options_(options) {}

Solution PointSolver::solve(const model::EvalPoint& nominal, model::ModelData& data) const {
  Solution s;
  const std::size_t oor_before = data.out_of_range_lookups;
  model::EvalPoint q = nominal;
  // e(n) gives the first iterate c1 = n − e(n); each further evaluation
  // measures the residual of the current iterate and moves it.
  Eigen::Vector3d e_mm = 1e-3 * model_->evaluate(q, data).e_um;
  s.iterations = 1;
  s.c = nominal.p - e_mm;
  while (true) {
    q.p = s.c;
    e_mm = 1e-3 * model_->evaluate(q, data).e_um;
    ++s.iterations;
    const Eigen::Vector3d r_mm = s.c + e_mm - nominal.p;
    s.residual_um = 1e3 * r_mm.norm();
    if (s.residual_um <= options_.tolerance_um) {
      s.converged = true;
      break;
    }
    if (s.iterations >= options_.max_iterations) break;
    s.c = nominal.p - e_mm;
  }
  s.out_of_range = data.out_of_range_lookups != oor_before;
  return s;
}

}  // namespace abbe::compensate
