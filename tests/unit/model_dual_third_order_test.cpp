// The dual model against a brute-force exact composition (rotation matrices
// from Eigen::AngleAxis, pivots at the measurement points): with every error
// scaled by λ the remainder |exact − (ε + ε²)| is third order, so halving λ
// divides it by ≈ 8.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "model_test_machines.hpp"

namespace abbe {
namespace {

using machine::Axis;
using model::ErrorModel;
using model::ModelKind;

// Exact P' − P (µm) from the looked-up errors of `data` at point p.
Eigen::Vector3d exact_displacement(const ErrorModel& model, const machine::Machine& m,
                                   const model::EvalPoint& p, const model::ModelData& data) {
  Eigen::Vector3d tip = p.p;  // mm
  const auto& order = m.chain().order();
  for (int c = 2; c >= 0; --c) {
    Axis j = order[static_cast<std::size_t>(c)];
    const auto& err = data.errors[static_cast<std::size_t>(index(j))];
    Eigen::Vector3d theta = 1e-6 * err.theta_urad;
    Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
    if (theta.norm() > 0.0) r = Eigen::AngleAxisd(theta.norm(), theta.normalized()).matrix();
    Eigen::Vector3d next;
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d mk = model.measurement_point(j, k, p);
      next[k] = (mk + 1e-3 * err.delta_um + r * (tip - mk))[k];
    }
    tip = next;
  }
  return 1e3 * (tip - p.p) +
         1e-3 * Eigen::Vector3d(-m.squareness().ec0y * p.p.y() + m.squareness().eb0z * p.p.z(),
                                -m.squareness().ea0z * p.p.z(), 0.0);
}

double remainder(const std::string& chain, const std::string& csv_at_lambda,
                 const model::EvalPoint& p, std::mt19937 rng_records) {
  auto spec = test::spec_with(chain, csv_at_lambda);
  test::randomize_records(spec, rng_records);
  spec.squareness = {20.0, -10.0, 5.0};
  machine::Machine m(std::move(spec));
  ErrorModel dual(m, ModelKind::dual);
  model::ModelData data;
  Eigen::Vector3d predicted = dual.evaluate(p, data).e_um;
  return (exact_displacement(dual, m, p, data) - predicted).norm();
}

std::string scaled_table(unsigned seed, double lambda) {
  std::mt19937 rng(seed);
  // λ = 1: 2 mm linear, 8 mrad angular — far beyond real machines, so the
  // third-order remainder stands well above rounding.
  return test::random_table(rng, 2000.0 * lambda, 8000.0 * lambda);
}

TEST(ModelDualThirdOrder, RemainderShrinksLikeLambdaCubed) {
  std::mt19937 rng(5);
  for (const std::string& chain : {std::string("w X' b Y Z t"), std::string("w b X Y Z t"),
                                   std::string("w Y' X' b Z t"), std::string("w Z' b Y X t")}) {
    for (unsigned seed = 10; seed < 14; ++seed) {
      auto p = test::random_point(rng);
      std::mt19937 records(seed);
      double r1 = remainder(chain, scaled_table(seed, 1.0), p, records);
      double r2 = remainder(chain, scaled_table(seed, 0.5), p, records);
      double r4 = remainder(chain, scaled_table(seed, 0.25), p, records);
      EXPECT_GT(r1, 1e-3) << "the remainder must stand above rounding";
      EXPECT_NEAR(r1 / r2, 8.0, 1.0) << chain << " seed " << seed;
      EXPECT_NEAR(r2 / r4, 8.0, 0.6) << chain << " seed " << seed;
    }
  }
}

// Without the ε² part the remainder is second order (ratio ≈ 4): the test
// above would notice a missing or wrong second-order term.
TEST(ModelDualThirdOrder, FirstOrderAloneIsOnlySecondOrderAccurate) {
  std::mt19937 rng(6);
  auto p = test::random_point(rng);
  double r[2];
  for (int i = 0; i < 2; ++i) {
    auto spec = test::spec_with("w X' b Y Z t", scaled_table(21, i == 0 ? 1.0 : 0.5));
    std::mt19937 records(21);
    test::randomize_records(spec, records);
    machine::Machine m(std::move(spec));
    ErrorModel dual(m, ModelKind::dual);
    model::ModelData data;
    model::Deviation d = dual.evaluate(p, data);
    r[i] = (exact_displacement(dual, m, p, data) - (d.e_um - d.second_order_um)).norm();
  }
  EXPECT_NEAR(r[0] / r[1], 4.0, 0.6);
}

}  // namespace
}  // namespace abbe
