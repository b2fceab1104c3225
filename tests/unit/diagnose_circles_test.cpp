// Circular tests (ISO 230-4) in the diagnosis (dynamic.hpp): the sets
// measured as circles are recognised; servo mismatch (an ellipse at 45°
// that turns with the direction of travel) and reversal spikes (peaks just
// after the quadrant points) left in the residual are reported as dynamic,
// out of scope, never named; clean circles report none.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "abbe/diagnose/diagnosis.hpp"
#include "abbe/diagnose/dynamic.hpp"

namespace abbe::diagnose {
namespace {

constexpr double kPi = 3.14159265358979323846;

enum class Signature { none, servo, spikes };

// A ballbar circle r = 150 mm in XY about (-450, -200, -150), a reading
// every 2°, CCW then CW, dn along the radius with noise 0.3 µm.
Problem circles(Signature sig, double amplitude, std::uint64_t seed) {
  Problem pb;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.3);
  const Eigen::Vector3d c(-450.0, -200.0, -150.0);
  std::vector<double> y;
  for (int travel : {1, -1})
    for (int k = 0; k < 180; ++k) {
      const double th = travel * 2.0 * kPi * k / 180.0;
      const Eigen::Vector3d n(std::cos(th), std::sin(th), 0.0);
      PointContext pc;
      pc.p = c + 150.0 * n;
      pc.s = pc.p;
      pc.set = "XY r150";
      // The last motion: along the tangent just before the reading.
      const double b = th - travel * 1e-6;
      pc.dir = {-travel * std::sin(b) > 0 ? 1 : -1, travel * std::cos(b) > 0 ? 1 : -1, 0};
      pc.t = 8.0 * static_cast<double>(pb.points.size());
      const auto ip = static_cast<std::uint32_t>(pb.points.size());
      pb.points.push_back(pc);
      pb.obs.push_back({ip, n});
      double v = noise(rng);
      if (sig == Signature::servo) v += travel * amplitude * std::sin(2.0 * th);
      if (sig == Signature::spikes) {
        double since = std::fmod(travel > 0 ? th : -th, 0.5 * kPi);
        if (since < 0.0) since += 0.5 * kPi;
        if (since > 1e-9 && since <= 6.0 * kPi / 180.0) v += amplitude;
      }
      y.push_back(v);
    }
  pb.y = Eigen::Map<Eigen::VectorXd>(y.data(), static_cast<Eigen::Index>(y.size()));
  pb.sets = {"XY r150"};
  pb.direction_present = {true, true, false};
  pb.var_lo = {-600.0, -350.0, -150.0, 0.0};
  pb.var_hi = {-300.0, -50.0, -150.0, 8.0 * 359};
  return pb;
}

Eigen::VectorXd demeaned(const Problem& pb) { return (pb.y.array() - pb.y.mean()).matrix(); }

TEST(DiagnoseCircles, CleanCirclesReportNothing) {
  const Problem pb = circles(Signature::none, 0.0, 1);
  const CircleCheck cc = check_circles(pb, demeaned(pb), 0.3);
  ASSERT_EQ(cc.circles, std::vector<std::string>{"XY r150"});
  EXPECT_TRUE(cc.findings.empty());
}

TEST(DiagnoseCircles, ServoMismatchInTheResidualIsDynamic) {
  const Problem pb = circles(Signature::servo, 1.5, 2);
  const CircleCheck cc = check_circles(pb, demeaned(pb), 0.3);
  ASSERT_EQ(cc.findings.size(), 1u);
  EXPECT_EQ(cc.findings[0].kind, "servo_mismatch");
  EXPECT_NEAR(cc.findings[0].amplitude_um, 1.5, 0.1);
}

TEST(DiagnoseCircles, ReversalSpikesAreDynamicAndNotNamed) {
  const Problem pb = circles(Signature::spikes, 3.0, 3);
  const CircleCheck cc = check_circles(pb, demeaned(pb), 0.3);
  ASSERT_EQ(cc.findings.size(), 1u);
  EXPECT_EQ(cc.findings[0].kind, "reversal_spikes");
  EXPECT_GT(cc.findings[0].amplitude_um, 1.5);  // 3 µm over 6° of the 10° window
  // Through the whole diagnosis: reported as dynamic, in the text too.
  const Diagnosis d = diagnose_problem(pb, DiagnoseOptions{});
  EXPECT_EQ(d.circles.size(), 1u);
  bool spikes = false;
  for (const DynamicFinding& f : d.dynamic) spikes = spikes || f.kind == "reversal_spikes";
  EXPECT_TRUE(spikes);
  const std::string text = report_text(d);
  EXPECT_NE(text.find("servo mismatch and reversal spikes are dynamic"), std::string::npos) << text;
  EXPECT_NE(text.find("dynamic, not named: reversal spikes in XY r150"), std::string::npos) << text;
}

TEST(DiagnoseCircles, OneWayOrNotACircleIsNotChecked) {
  Problem pb = circles(Signature::servo, 1.5, 4);
  // Not radial: the normals turned by 90°.
  Problem turned = pb;
  for (auto& ob : turned.obs) ob.u = Eigen::Vector3d(-ob.u.y(), ob.u.x(), 0.0);
  EXPECT_TRUE(check_circles(turned, demeaned(turned), 0.3).circles.empty());
  // dx measurements (not dn): not a circle either.
  Problem grid = pb;
  for (auto& ob : grid.obs) ob.u = Eigen::Vector3d::UnitX();
  EXPECT_TRUE(check_circles(grid, demeaned(grid), 0.3).circles.empty());
}

}  // namespace
}  // namespace abbe::diagnose
