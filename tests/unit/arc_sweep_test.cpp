// One arc rule for the fragmenter (path::ArcSpan) and the compensator and
// verifier (compensate::MotionPath): the same signed sweep for every arc,
// including the full circles and the very short arcs at the edge of the rule.
#include <gtest/gtest.h>

#include <cmath>

#include "abbe/compensate/motion_path.hpp"
#include "abbe/io/units.hpp"
#include "abbe/path/arc_span.hpp"

namespace abbe::path {
namespace {

gcode::Motion arc(double end_angle, int rotation, double radius = 100.0) {
  gcode::Motion m;
  m.kind = gcode::MotionKind::arc;
  m.plane = gcode::Plane::xy;
  m.center = Eigen::Vector3d(10.0, -20.0, 0.0);
  m.start = m.center + Eigen::Vector3d(radius, 0.0, 0.0);
  m.end = m.center + radius * Eigen::Vector3d(std::cos(end_angle), std::sin(end_angle), 0.0);
  m.rotation = rotation;
  return m;
}

TEST(ArcSweep, FragmenterAndCompensatorAgree) {
  const double pi = units::kPi;
  struct Case {
    double end_angle;
    int rotation;
    double sweep;
  };
  const Case cases[] = {
      {0.5 * pi, 1, 0.5 * pi},          // quarter, counter-clockwise
      {0.5 * pi, -1, -1.5 * pi},        // the same end clockwise
      {0.0, 1, 2.0 * pi},               // start = end: a full circle
      {0.0, -3, -6.0 * pi},             // three full turns clockwise
      {pi, 2, 3.0 * pi},                // half plus one turn
      {2e-6, 1, 2e-6},                  // 2 µrad: a very short arc, not a circle
      {-2e-6, -1, -2e-6},               // the same clockwise
      {5e-11, 1, 2.0 * pi + 5e-11},     // below LinuxCNC's 1e-6 rad: one turn more
      {-5e-11, -1, -2.0 * pi - 5e-11},  // the same clockwise
      {5e-13, 1, 2.0 * pi},             // chord 5e-11 mm: a full circle
  };
  for (const Case& c : cases) {
    const gcode::Motion m = arc(c.end_angle, c.rotation);
    const double a = ArcSpan(m).sweep();
    const double b = compensate::MotionPath(m).sweep();
    EXPECT_NEAR(a, c.sweep, 1e-12) << c.end_angle << " " << c.rotation;
    EXPECT_EQ(a, b) << c.end_angle << " " << c.rotation;
  }
}

TEST(ArcSweep, RuleIsTheChordInMillimetresAndLinuxCncsSweepFuzz) {
  EXPECT_EQ(arc_sweep(0.3, 0.3, 0.5 * kFullCircleChord, 1), units::kTwoPi);
  EXPECT_EQ(arc_sweep(0.3, 0.3, 0.5 * kFullCircleChord, -2), -2.0 * units::kTwoPi);
  // A sweep below 1e-6 rad (LinuxCNC's CIRCLE_FUZZ) is a full circle more.
  EXPECT_NEAR(arc_sweep(0.3, 0.3 + 1e-12, 2.0 * kFullCircleChord, 1), units::kTwoPi + 1e-12, 1e-12);
  EXPECT_NEAR(arc_sweep(0.3, 0.3 + 0.9e-6, 1.0, 1), units::kTwoPi + 0.9e-6, 1e-12);
  EXPECT_NEAR(arc_sweep(0.3, 0.3 + 1.1e-6, 1.0, 1), 1.1e-6, 1e-12);
  EXPECT_NEAR(arc_sweep(0.3 + 0.9e-6, 0.3, 1.0, -1), -units::kTwoPi - 0.9e-6, 1e-12);
}

}  // namespace
}  // namespace abbe::path
