// Table lookups inside the models: direction of motion, interpolation and
// the out-of-range policies.
#include <gtest/gtest.h>

#include "abbe/io/input_error.hpp"
#include "model_test_machines.hpp"

namespace abbe {
namespace {

using model::ErrorModel;
using model::ModelKind;

model::EvalPoint at_x(double x, int dir_x = 0) {
  model::EvalPoint p;
  p.p = {x, -100.0, -100.0};
  p.tool_length = 0.0;
  p.dir = {static_cast<std::int8_t>(dir_x), 0, 0};
  return p;
}

TEST(ModelTableLookup, BidirectionalUsesTheDirectionOfMotion) {
  // EXX fwd 1 → 3, rev 5 → 9 on different grids; EYX mean only.
  std::string csv = std::string(test::kHeader) +
                    "X,EXX,-400,fwd,1\nX,EXX,0,fwd,3\n"
                    "X,EXX,-400,rev,5\nX,EXX,-200,rev,7\nX,EXX,0,rev,9\n"
                    "X,EYX,-400,mean,2\nX,EYX,0,mean,4\n";
  machine::Machine m(test::spec_with("w X' b Y Z t", csv));
  ErrorModel ae(m, ModelKind::ae_arm);
  model::ModelData data;
  for (int dir : {1, -1, 0}) {
    Eigen::Vector3d e = ae.evaluate(at_x(-100.0, dir), data).e_um;
    double fwd = 1.0 + 2.0 * 300.0 / 400.0;  // 2.5
    double rev = 7.0 + 2.0 * 100.0 / 200.0;  // 8
    double expected = dir > 0 ? fwd : dir < 0 ? rev : 0.5 * (fwd + rev);
    EXPECT_NEAR(e.x(), expected, 1e-12) << "dir " << dir;
    EXPECT_NEAR(e.y(), 3.5, 1e-12) << "mean serves every direction";
  }
  EXPECT_EQ(data.out_of_range_lookups, 0u);
}

TEST(ModelTableLookup, InterpolatesAlongAPathBothWays) {
  std::string csv = std::string(test::kHeader);
  for (int i = 0; i <= 20; ++i)
    csv += fmt::format("X,EXX,{},mean,{}\n", -1000 + 50 * i, (i % 3) * 1.5 - 0.25 * i);
  machine::Machine m(test::spec_with("w X' b Y Z t", csv));
  ErrorModel ae(m, ModelKind::ae_arm);
  model::ModelData data;
  const auto& s = m.table().series().front();
  auto reference = [&](double x) {
    std::size_t i = static_cast<std::size_t>((x + 1000.0) / 50.0);
    if (i >= 20) i = 19;
    double t = (x - s.position_mm[i]) / 50.0;
    return s.value[i] + t * (s.value[i + 1] - s.value[i]);
  };
  // Forward, backward and jumping: the cached segment must never be stale.
  std::vector<double> xs;
  for (double x = -1000.0; x <= 0.0; x += 7.3) xs.push_back(x);
  for (double x = 0.0; x >= -1000.0; x -= 11.1) xs.push_back(x);
  for (double x : {-10.0, -990.0, -500.0, 0.0, -1000.0, -475.0}) xs.push_back(x);
  for (double x : xs) EXPECT_NEAR(ae.evaluate(at_x(x), data).e_um.x(), reference(x), 1e-12) << x;
}

std::string short_table() {
  return std::string(test::kHeader) + "X,EXX,-400,mean,1\nX,EXX,-200,mean,3\n";
}

TEST(ModelTableLookup, ClampCountsLookupsOutsideTheRange) {
  machine::Machine m(test::spec_with("w X' b Y Z t", short_table()));
  EXPECT_EQ(m.out_of_range(), machine::OutOfRangePolicy::clamp);
  ErrorModel ae(m, ModelKind::ae_arm);
  model::ModelData data;
  EXPECT_NEAR(ae.evaluate(at_x(-300.0), data).e_um.x(), 2.0, 1e-12);
  EXPECT_EQ(data.out_of_range_lookups, 0u);
  EXPECT_NEAR(ae.evaluate(at_x(-100.0), data).e_um.x(), 3.0, 1e-12);
  EXPECT_NEAR(ae.evaluate(at_x(-900.0), data).e_um.x(), 1.0, 1e-12);
  EXPECT_EQ(data.out_of_range_lookups, 2u);
  // Axes without data are never out of range.
  EXPECT_EQ(data.evaluations, 3u);
}

TEST(ModelTableLookup, ExtrapolateContinuesTheEndSegments) {
  auto spec = test::spec_with("w X' b Y Z t", short_table());
  spec.out_of_range = machine::OutOfRangePolicy::extrapolate;
  machine::Machine m(std::move(spec));
  ErrorModel ae(m, ModelKind::ae_arm);
  model::ModelData data;
  EXPECT_NEAR(ae.evaluate(at_x(-100.0), data).e_um.x(), 4.0, 1e-12);
  EXPECT_NEAR(ae.evaluate(at_x(-500.0), data).e_um.x(), 0.0, 1e-12);
  EXPECT_EQ(data.out_of_range_lookups, 2u);
}

TEST(ModelTableLookup, ErrorPolicyNamesTheAxisAndPosition) {
  auto spec = test::spec_with("w X' b Y Z t", short_table());
  spec.out_of_range = machine::OutOfRangePolicy::error;
  machine::Machine m(std::move(spec));
  ErrorModel ae(m, ModelKind::ae_arm);
  model::ModelData data;
  EXPECT_NO_THROW(ae.evaluate(at_x(-250.0), data));
  try {
    ae.evaluate(at_x(-150.0), data);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().field, "X");
    EXPECT_NE(e.message().find("-150"), std::string::npos) << e.message();
    EXPECT_NE(e.message().find("[-400, -200]"), std::string::npos) << e.message();
  }
}

}  // namespace
}  // namespace abbe
