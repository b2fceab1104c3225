// Table lookups inside the models: direction of motion, interpolation and
// the out-of-range policies.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

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

// Uneven knots: the segment guessed from the first spacing is off by many
// segments, too high or too low (stepping and bisection find it), and an
// evenly spaced table with a shorter last segment (a travel that is not a
// multiple of the spacing).
TEST(ModelTableLookup, UnevenKnotsInterpolateLikeTheSeries) {
  const std::vector<std::vector<double>> grids = {
      {-1000, -999, -998, -990, -900, -899, -500, -499.5, -100, -10, -9, 0},
      {-1000, -100, -99, -98, -97, -96, -95, -94, -93, -92, -91, -90, -50, 0},
      {-990, -965, -940, -915, -890, -865, -840, -815, -790, -765, -740, -715, -690, -665,
       -640, -615, -590, -565, -540, -515, -490, -465, -440, -415, -390, -365, -340, -315,
       -290, -265, -240, -215, -190, -165, -140, -115, -90,  -65,  -40,  -15,  0}};
  for (const auto& grid : grids) {
    std::string csv = std::string(test::kHeader);
    std::vector<double> values;
    for (std::size_t i = 0; i < grid.size(); ++i) {
      values.push_back(std::sin(0.37 * static_cast<double>(i)) * 5.0 + 0.01 * grid[i]);
      csv += fmt::format("X,EXX,{},mean,{:.6f}\n", grid[i], values.back());
    }
    machine::Machine m(test::spec_with("w X' b Y Z t", csv));
    ErrorModel ae(m, ModelKind::ae_arm);
    model::ModelData data;
    const auto& s = m.table().series().front();
    auto reference = [&](double x) {
      if (x <= grid.front()) return s.value.front();
      if (x >= grid.back()) return s.value.back();
      std::size_t i = 0;
      while (grid[i + 1] <= x) ++i;
      const double t = (x - grid[i]) / (grid[i + 1] - grid[i]);
      return s.value[i] + t * (s.value[i + 1] - s.value[i]);
    };
    std::vector<double> xs(grid);  // every knot exactly
    for (double x = -1010.0; x <= 10.0; x += 0.73) xs.push_back(x);
    for (double x = 5.0; x >= -1005.0; x -= 13.1) xs.push_back(x);
    for (double x : {-999.5, -0.5, -1000.0, 0.0, -9.5, -499.75, -14.9, -15.0, -15.1})
      xs.push_back(x);
    for (double x : xs) EXPECT_NEAR(ae.evaluate(at_x(x), data).e_um.x(), reference(x), 1e-11) << x;
  }
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

// A machine with the short EXX table and the given out-of-range policy.
machine::Machine short_machine(machine::OutOfRangePolicy policy) {
  auto spec = test::spec_with("w X' b Y Z t", short_table());
  spec.out_of_range = policy;
  return machine::Machine(std::move(spec));
}

TEST(ModelTableLookup, ExtrapolateContinuesTheEndSegments) {
  const machine::Machine m = short_machine(machine::OutOfRangePolicy::extrapolate);
  ErrorModel ae(m, ModelKind::ae_arm);
  model::ModelData data;
  EXPECT_NEAR(ae.evaluate(at_x(-100.0), data).e_um.x(), 4.0, 1e-12);
  EXPECT_NEAR(ae.evaluate(at_x(-500.0), data).e_um.x(), 0.0, 1e-12);
  EXPECT_EQ(data.out_of_range_lookups, 2u);
}

TEST(ModelTableLookup, ErrorPolicyNamesTheAxisAndPosition) {
  const machine::Machine m = short_machine(machine::OutOfRangePolicy::error);
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
