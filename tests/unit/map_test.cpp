// Workspace map on a tiny machine whose errors are computed by hand: one
// constant pitch EBX = 10 µrad of the table axis X, measured with the
// reflector at M = (−800, −256, −478). htm uses the arm P (from machine
// zero), ae-arm the arm P − M: d = ε_y·(a_z, 0, −a_x).
#include <gtest/gtest.h>

#include <cmath>

#include "abbe/identify/workspace_map.hpp"
#include "abbe/machine/machine.hpp"

namespace abbe::identify {
namespace {

machine::Machine tiny_machine() {
  machine::MachineSpec spec;
  spec.name = "tiny";
  spec.file = "<tiny>";
  spec.chain = machine::KinematicChain::parse("w X' b Y Z t");
  spec.travel = {machine::Travel{-1000, 0}, machine::Travel{-500, 0}, machine::Travel{-500, 0}};
  spec.tool_length = 0.0;
  machine::AxisRecord& x = spec.axes[0];
  x.present = true;
  x.measured_tip = {-500, -256, -280};
  x.point = {Eigen::Vector3d(-800, -256, -478), Eigen::Vector3d(-800, -256, -478),
             Eigen::Vector3d(-800, -256, -478)};
  spec.table = machine::ComponentTable::parse(
      "axis,component,position_mm,direction,value\nX,EBX,-1000,mean,10\nX,EBX,0,mean,10\n",
      "<tiny.csv>");
  return machine::Machine(spec);
}

TEST(WorkspaceMap, GridAxisIncludesBothEnds) {
  const auto v = grid_axis(-400, -200, 100);
  ASSERT_EQ(v.size(), 3u);
  EXPECT_DOUBLE_EQ(v[0], -400);
  EXPECT_DOUBLE_EQ(v[2], -200);
  const auto w = grid_axis(0, 250, 100);  // step shrinks to 83.3 so 250 is a point
  ASSERT_EQ(w.size(), 4u);
  EXPECT_DOUBLE_EQ(w[3], 250);
  EXPECT_EQ(grid_axis(5, 5, 50).size(), 1u);
}

TEST(WorkspaceMap, StatisticsOfHandComputedErrors) {
  const machine::Machine m = tiny_machine();
  MapOptions opt;
  opt.lo = {-400, -300, -300};
  opt.hi = {-200, -100, -200};
  opt.spacing_mm = 100;
  const WorkspaceMap map = compute_map(m, opt);
  ASSERT_EQ(map.points.size(), 18u);
  ASSERT_EQ(map.stats.size(), 3u);
  // By hand: 10 µrad × mm = 0.01 µm.
  double sh = 0, sa = 0, s2h = 0, s2a = 0, mh = 0, ma = 0, sdiff = 0, m2 = 0;
  for (const Eigen::Vector3d& p : map.points) {
    const Eigen::Vector3d h(0.01 * p.z(), 0.0, -0.01 * p.x());
    const Eigen::Vector3d a(0.01 * (p.z() + 478), 0.0, -0.01 * (p.x() + 800));
    sh += h.norm();
    sa += a.norm();
    s2h += h.squaredNorm();
    s2a += a.squaredNorm();
    mh = std::max(mh, h.norm());
    ma = std::max(ma, a.norm());
    sdiff += (h - a).norm();
    // ε² part of the dual model: ½[θ]²·arm = −½ε²·(a_x, 0, a_z), ε = 1e-5 rad, mm → µm.
    m2 = std::max(m2, 0.5e-10 * 1e3 * std::hypot(p.x() + 800, p.z() + 478));
  }
  const double n = 18.0;
  const ModelMapStats& h = map.stats[0];
  const ModelMapStats& a = map.stats[1];
  EXPECT_EQ(h.model, model::ModelKind::htm);
  EXPECT_NEAR(h.mean_um, sh / n, 1e-9);
  EXPECT_NEAR(h.rms_um, std::sqrt(s2h / n), 1e-9);
  EXPECT_NEAR(h.max_um, mh, 1e-9);
  EXPECT_NEAR(a.mean_um, sa / n, 1e-9);
  EXPECT_NEAR(a.rms_um, std::sqrt(s2a / n), 1e-9);
  EXPECT_NEAR(a.max_um, ma, 1e-9);
  ASSERT_TRUE(map.has_comparison);
  EXPECT_NEAR(map.percent_smaller, 100.0 * (sh - sa) / sh, 1e-9);
  EXPECT_NEAR(map.mean_abs_vector_difference_um, sdiff / n, 1e-9);
  // dual = ae-arm plus the second-order part.
  EXPECT_NEAR(map.stats[2].mean_um, a.mean_um, 1e-4);
  EXPECT_NEAR(map.stats[2].second_order_max_um, m2, 1e-12);
  EXPECT_GT(m2, 1e-5);
}

TEST(WorkspaceMap, CsvAndSlices) {
  const machine::Machine m = tiny_machine();
  MapOptions opt;
  opt.lo = {-400, -300, -300};
  opt.hi = {-200, -100, -200};
  opt.spacing_mm = 100;
  opt.models = {model::ModelKind::ae_arm};
  const WorkspaceMap map = compute_map(m, opt);
  const std::string csv = map_to_csv(map);
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "x,y,z,ae-arm_dx,ae-arm_dy,ae-arm_dz,ae-arm_d");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 19);
  // First point (−400, −300, −300): d = (0.01·178, 0, −0.01·400).
  EXPECT_NE(csv.find("\n-400,-300,-300,1.78,0,-4,4.3781"), std::string::npos) << csv;
  const std::string xy = map_slice_csv(map, "xy", 1);
  EXPECT_EQ(std::count(xy.begin(), xy.end(), '\n'), 10);
  EXPECT_NE(xy.find("\n-400,-300,-200,"), std::string::npos);
  const std::string yz = map_slice_csv(map, "yz", 0);
  EXPECT_EQ(yz.substr(0, 6), "y,z,x,");
  EXPECT_EQ(std::count(yz.begin(), yz.end(), '\n'), 7);
  EXPECT_THROW(map_slice_csv(map, "xy", 2), std::out_of_range);
  EXPECT_THROW(map_slice_csv(map, "ab", 0), std::invalid_argument);
  EXPECT_FALSE(map.has_comparison);
}

}  // namespace
}  // namespace abbe::identify
