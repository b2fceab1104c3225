// PointSolver: predicted(c) = c + e(c) reaches the nominal point to 0.01 µm
// in at most 5 model evaluations; an all-zero machine leaves every point.
#include <gtest/gtest.h>

#include "abbe/compensate/point_solver.hpp"
#include "abbe/machine/machine.hpp"

namespace abbe::compensate {
namespace {

const std::string kSample = std::string(ABBE_SOURCE_DIR) + "/machines/sample/machine.yaml";
const std::string kZero = std::string(ABBE_TEST_DATA_DIR) + "/compensate/zero.yaml";

TEST(CompensateSolver, ReachesTheNominalPointForEveryModel) {
  const machine::Machine m = machine::Machine::load(kSample);
  for (auto kind : {model::ModelKind::htm, model::ModelKind::ae_arm, model::ModelKind::dual}) {
    const model::ErrorModel em(m, kind);
    const PointSolver solver(em);
    model::ModelData data;
    for (double x : {-900.0, -500.0, -120.0})
      for (double y : {-450.0, -250.0, -30.0}) {
        model::EvalPoint n;
        n.p = Eigen::Vector3d(x, y, -300.0);
        n.tool_length = 200.0;
        n.dir = {1, -1, 0};
        const Solution s = solver.solve(n, data);
        ASSERT_TRUE(s.converged);
        EXPECT_LE(s.iterations, 5);
        // Independent check: the model at c predicts the nominal point.
        model::EvalPoint c = n;
        c.p = s.c;
        model::ModelData fresh;
        const Eigen::Vector3d predicted = s.c + 1e-3 * em.evaluate(c, fresh).e_um;
        EXPECT_LT(1e3 * (predicted - n.p).norm(), 0.01);
        EXPECT_GT(1e3 * (s.c - n.p).norm(), 1.0);  // the sample machine has µm errors
      }
  }
}

// The ae-arm solution for nominal point p (tool length 200 mm) on a machine file.
Solution solve_on(const std::string& machine_file, const Eigen::Vector3d& p,
                  const SolverOptions& o = {}) {
  const machine::Machine m = machine::Machine::load(machine_file);
  const model::ErrorModel em(m, model::ModelKind::ae_arm);
  model::ModelData data;
  model::EvalPoint n;
  n.p = p;
  n.tool_length = 200.0;
  return PointSolver(em, o).solve(n, data);
}

TEST(CompensateSolver, ZeroTablesLeaveThePointExactly) {
  const Eigen::Vector3d p(-333.3333, -123.4567, -287.0001);
  const Solution s = solve_on(kZero, p);
  EXPECT_TRUE(s.converged);
  EXPECT_EQ(s.c, p);
}

TEST(CompensateSolver, ReportsNonConvergence) {
  SolverOptions o;
  o.tolerance_um = 0.0;  // unreachable
  o.max_iterations = 2;
  const Solution s = solve_on(kSample, Eigen::Vector3d(-500.0, -250.0, -300.0), o);
  EXPECT_FALSE(s.converged);
  EXPECT_EQ(s.iterations, 2);
}

}  // namespace
}  // namespace abbe::compensate
