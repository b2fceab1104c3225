// The worked examples of docs/models.md (chain w X' b Y Z t, tool length
// unchanged, q = P = (−300, −200, −250) mm), exact numbers.
#include <gtest/gtest.h>

#include <Eigen/Geometry>  // cross()

#include "model_test_machines.hpp"

namespace abbe {
namespace {

using model::ErrorModel;
using model::ModelKind;

constexpr double kTol = 1e-9;  // µm

model::EvalPoint example_point(double l) {
  model::EvalPoint p;
  p.p = {-300.0, -200.0, -250.0};
  p.tool_length = l;
  return p;
}

Eigen::Vector3d predict(const machine::Machine& m, ModelKind kind, const model::EvalPoint& p,
                        Eigen::Vector3d* second = nullptr) {
  ErrorModel model(m, kind);
  model::ModelData data;
  model::Deviation d = model.evaluate(p, data);
  if (second) *second = d.second_order_um;
  return d.e_um;
}

void expect_near(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double tol) {
  EXPECT_NEAR(a.x(), b.x(), tol) << a.transpose() << " vs " << b.transpose();
  EXPECT_NEAR(a.y(), b.y(), tol) << a.transpose() << " vs " << b.transpose();
  EXPECT_NEAR(a.z(), b.z(), tol) << a.transpose() << " vs " << b.transpose();
}

TEST(ModelWorkedExamples, TableAxisPitch) {
  const double L = 130.0;
  auto spec =
      test::spec_with("w X' b Y Z t", std::string(test::kHeader) + test::constant_rows("EBX", 10.0),
                      {-500.0, -256.0, -280.0}, L, {-800.0, -256.0, -478.0});
  machine::Machine m(std::move(spec));
  auto p = example_point(L);
  expect_near(predict(m, ModelKind::ae_arm, p), {2.28, 0.0, -5.00}, kTol);
  expect_near(predict(m, ModelKind::htm, p), {-2.50, 0.0, 3.00}, kTol);
  Eigen::Vector3d second;
  Eigen::Vector3d dual = predict(m, ModelKind::dual, p, &second);
  expect_near(dual - second, {2.28, 0.0, -5.00}, kTol);
  // ε² part: ½[θ]²·arm = ½ θ × (θ × arm), arm = (500, 56, 228) mm.
  const Eigen::Vector3d theta(0.0, 10e-6, 0.0), arm(500.0, 56.0, 228.0);
  expect_near(second, 1e3 * 0.5 * theta.cross(theta.cross(arm)), 1e-15);
}

TEST(ModelWorkedExamples, ToolSideRoll) {
  const double L = 130.0;
  // Y measured with the tip at x = −500, z = −280; optic at z = −300.
  auto spec =
      test::spec_with("w X' b Y Z t", std::string(test::kHeader) + test::constant_rows("EAY", 20.0),
                      {-500.0, -256.0, -280.0}, L, {-500.0, -256.0, -300.0});
  machine::Machine m(std::move(spec));
  auto p = example_point(L);
  ErrorModel ae(m, ModelKind::ae_arm);
  expect_near(ae.measurement_point(machine::Axis::y, 1, p), {-300.0, -200.0, -300.0}, 1e-12);
  expect_near(ae.frame_origin(machine::Axis::y, p), {-300.0, -200.0, 0.0}, 1e-12);
  expect_near(predict(m, ModelKind::ae_arm, p), {0.0, -1.00, 0.0}, kTol);
  expect_near(predict(m, ModelKind::htm, p), {0.0, 5.00, 0.0}, kTol);
  Eigen::Vector3d second;
  Eigen::Vector3d dual = predict(m, ModelKind::dual, p, &second);
  expect_near(dual - second, {0.0, -1.00, 0.0}, kTol);
}

TEST(ModelWorkedExamples, SquarenessOnly) {
  auto spec = test::spec_with("w X' b Y Z t", test::kHeader);
  spec.squareness = {14.569, -24.362, 13.757};
  machine::Machine m(std::move(spec));
  for (ModelKind k : {ModelKind::htm, ModelKind::ae_arm, ModelKind::dual})
    expect_near(predict(m, k, example_point(100.0)), {9.0043, 3.43925, 0.0}, 1e-9);
}

}  // namespace
}  // namespace abbe
