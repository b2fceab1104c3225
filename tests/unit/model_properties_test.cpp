// Properties of the three error models at random points and random chains.
#include <gtest/gtest.h>

#include <Eigen/Geometry>  // cross()

#include "model_test_machines.hpp"

namespace abbe {
namespace {

using machine::Axis;
using model::ErrorModel;
using model::ModelKind;

constexpr ModelKind kAll[] = {ModelKind::htm, ModelKind::ae_arm, ModelKind::dual};

TEST(ModelProperties, ZeroTablesPredictExactlyZero) {
  std::mt19937 rng(1);
  // An empty table and a table of explicit zeros.
  std::string zeros = test::kHeader;
  for (char a : {'X', 'Y', 'Z'})
    for (char d : {'X', 'Y', 'Z', 'A', 'B', 'C'})
      zeros += fmt::format(
          "{0},E{1}{0},-500,fwd,0\n{0},E{1}{0},0,fwd,0\n{0},E{1}{0},-500,rev,0\n"
          "{0},E{1}{0},0,rev,0\n",
          a, d);
  for (const std::string& csv : {std::string(test::kHeader), zeros})
    for (const std::string& chain : test::all_chains()) {
      auto spec = test::spec_with(chain, csv);
      test::randomize_records(spec, rng);
      machine::Machine m(std::move(spec));
      for (ModelKind k : kAll) {
        ErrorModel model(m, k);
        model::ModelData data;
        for (int i = 0; i < 20; ++i) {
          model::Deviation d = model.evaluate(test::random_point(rng), data);
          EXPECT_EQ(d.e_um, Eigen::Vector3d::Zero()) << chain << " " << to_string(k);
          EXPECT_EQ(d.second_order_um, Eigen::Vector3d::Zero());
        }
      }
    }
}

TEST(ModelProperties, SquarenessAloneFollowsTheFormula) {
  std::mt19937 rng(2);
  auto spec = test::spec_with("w Y' X' b Z t", test::kHeader);
  spec.squareness = {-7.5, 30.25, 11.0};
  machine::Machine m(std::move(spec));
  for (ModelKind k : kAll) {
    ErrorModel model(m, k);
    model::ModelData data;
    for (int i = 0; i < 50; ++i) {
      auto p = test::random_point(rng);
      Eigen::Vector3d e = model.evaluate(p, data).e_um;
      const double x = p.p.x(), y = p.p.y(), z = p.p.z();
      (void)x;
      EXPECT_NEAR(e.x(), 1e-3 * (7.5 * y + 30.25 * z), 1e-12);
      EXPECT_NEAR(e.y(), 1e-3 * (-11.0 * z), 1e-12);
      EXPECT_EQ(e.z(), 0.0);
    }
  }
}

// htm − ae-arm = Σ_j [ε_j × (M_{j,k}(q) − O_j(q))]_k, up to the second-order
// products the htm chain carries (kept tiny here: errors of ~1 µm, 1 µrad).
TEST(ModelProperties, HtmMinusAeArmIsTheArmOffset) {
  std::mt19937 rng(3);
  for (const std::string& chain : test::all_chains()) {
    auto spec = test::spec_with(chain, test::random_table(rng, 1.0, 1.0));
    test::randomize_records(spec, rng);
    machine::Machine m(std::move(spec));
    ErrorModel htm(m, ModelKind::htm), ae(m, ModelKind::ae_arm);
    model::ModelData dh, da;
    double largest = 0.0;
    for (int i = 0; i < 30; ++i) {
      auto p = test::random_point(rng);
      Eigen::Vector3d diff = htm.evaluate(p, dh).e_um - ae.evaluate(p, da).e_um;
      Eigen::Vector3d expected = Eigen::Vector3d::Zero();
      for (Axis j : machine::kAxes) {
        const Eigen::Vector3d& theta = da.errors[static_cast<std::size_t>(index(j))].theta_urad;
        for (int k = 0; k < 3; ++k)
          expected[k] +=
              1e-3 * theta.cross(ae.measurement_point(j, k, p) - ae.frame_origin(j, p))[k];
      }
      largest = std::max(largest, expected.cwiseAbs().maxCoeff());
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(diff[k], expected[k], 1e-5) << chain;
    }
    EXPECT_GT(largest, 0.1) << "the arms must differ for the test to mean anything";
  }
}

TEST(ModelProperties, DualFirstOrderPartIsAeArm) {
  std::mt19937 rng(4);
  for (const std::string& chain : test::all_chains()) {
    auto spec = test::spec_with(chain, test::random_table(rng, 20.0, 50.0));
    test::randomize_records(spec, rng);
    spec.squareness = {3.0, -4.0, 5.0};
    machine::Machine m(std::move(spec));
    ErrorModel dual(m, ModelKind::dual), ae(m, ModelKind::ae_arm);
    model::ModelData dd, da;
    for (int i = 0; i < 30; ++i) {
      auto p = test::random_point(rng);
      model::Deviation d = dual.evaluate(p, dd);
      Eigen::Vector3d a = ae.evaluate(p, da).e_um;
      Eigen::Vector3d first = d.e_um - d.second_order_um;
      double scale = std::max(1.0, a.cwiseAbs().maxCoeff());
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(first[k], a[k], 1e-12 * scale) << chain;
      EXPECT_GT(d.second_order_um.norm(), 0.0);
      EXPECT_LT(d.second_order_um.norm(), 1e-2 * std::max(a.norm(), 1.0));
    }
  }
}

// In w X' b Y Z t a table axis' arm follows its own position (the table
// moves under the tool); a tool-side axis' arm does not (its reflector rides
// along with the tool).
TEST(ModelProperties, TableAxisArmMovesToolSideArmDoesNot) {
  const std::string csv = std::string(test::kHeader) + test::constant_rows("EBX", 10.0) +
                          test::constant_rows("EAY", 20.0);
  machine::Machine m(
      test::spec_with("w X' b Y Z t", csv, {-500, -256, -280}, 100.0, {-800, -256, -478}));
  ErrorModel ae(m, ModelKind::ae_arm);
  model::ModelData data;
  model::EvalPoint a, b, c;
  a.p = {-300, -200, -250};
  a.tool_length = 100.0;
  b = a;
  b.p.x() -= 100.0;  // X moves
  c = a;
  c.p.y() -= 100.0;  // Y moves
  Eigen::Vector3d ea = ae.evaluate(a, data).e_um;
  Eigen::Vector3d eb = ae.evaluate(b, data).e_um;
  Eigen::Vector3d ec = ae.evaluate(c, data).e_um;
  // X: e_z = −EBX·(x − M_x): moving X by −100 mm adds +1.0 µm.
  EXPECT_NEAR(eb.z() - ea.z(), 1.0, 1e-12);
  EXPECT_EQ(ae.measurement_point(Axis::x, 0, a), ae.measurement_point(Axis::x, 0, b));
  // Y: its arm rides with Y, so moving Y changes nothing.
  EXPECT_NEAR((ec - ea).norm(), 0.0, 1e-12);
  EXPECT_NEAR((ae.measurement_point(Axis::y, 1, c) - ae.measurement_point(Axis::y, 1, a)).y(),
              -100.0, 1e-12);
}

// A tool longer than the one used while measuring puts the tip further from
// the tool-side carriages: at fixed axis positions s the tool-side arms gain
// −(L − L_meas)·e_z; at a fixed tip P the workpiece-side arms do not change.
TEST(ModelProperties, ToolLengthRule) {
  const std::string csv = std::string(test::kHeader) + test::constant_rows("EBX", 10.0) +
                          test::constant_rows("EAZ", 20.0);
  const double l_meas = 100.0, dl = 60.0;
  machine::Machine m(
      test::spec_with("w X' b Y Z t", csv, {-500, -256, -280}, l_meas, {-600, -300, -350}));
  ErrorModel ae(m, ModelKind::ae_arm);
  model::ModelData data;
  model::EvalPoint base;
  base.p = {-300, -200, -250};
  base.tool_length = l_meas;
  // Fixed s, longer tool: the Z reflector arm (tool side) changes by −dl·e_z.
  model::EvalPoint longer = base;
  longer.p.z() -= dl;
  longer.tool_length += dl;
  Eigen::Vector3d arm0 = base.p - ae.measurement_point(Axis::z, 1, base);
  Eigen::Vector3d arm1 = longer.p - ae.measurement_point(Axis::z, 1, longer);
  EXPECT_NEAR((arm1 - arm0 - Eigen::Vector3d(0, 0, -dl)).norm(), 0.0, 1e-12);
  // EAZ = 20 µrad: e_y = −θ_A·arm_z → changes by +20e-3·dl µm.
  Eigen::Vector3d e0 = ae.evaluate(base, data).e_um;
  // Fixed P, longer tool: only the tool-side arm changes (by −dl·e_z again).
  model::EvalPoint same_tip = base;
  same_tip.tool_length += dl;
  Eigen::Vector3d e2 = ae.evaluate(same_tip, data).e_um;
  EXPECT_NEAR(e2.y() - e0.y(), 20e-3 * dl, 1e-12);
  EXPECT_EQ(ae.measurement_point(Axis::x, 0, same_tip), ae.measurement_point(Axis::x, 0, base));
  EXPECT_NEAR(e2.x() - e0.x(), 0.0, 1e-12);  // EBX term: no L dependence at fixed P
  EXPECT_NEAR(e2.z() - e0.z(), 0.0, 1e-12);
}

}  // namespace
}  // namespace abbe
