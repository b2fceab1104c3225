// Arcs: IJK and R forms, G90.1/G91.1, turns, helices, full circles, the three
// planes (LinuxCNC's axis order and rotation sign), and the arc errors.
#include <gtest/gtest.h>

#include <cmath>

#include "interpreter_checks.hpp"
#include "test_blocks.hpp"

namespace abbe::gcode {
namespace {

using testing::error_of;
using testing::expect_near;
using testing::run_lines;

TEST(InterpreterArc, G3IncrementalCentreQuarterCircle) {
  const auto m = run_lines({"G0 X10 Y0 Z0", "G3 X0 Y10 I-10 J0 F100"});
  ASSERT_EQ(m.size(), 2u);
  EXPECT_EQ(m[1].kind, MotionKind::arc);
  EXPECT_EQ(m[1].plane, Plane::xy);
  EXPECT_EQ(m[1].rotation, 1);
  expect_near(m[1].start, {10, 0, 0});
  expect_near(m[1].end, {0, 10, 0});
  expect_near(m[1].center, {0, 0, 0});
  EXPECT_DOUBLE_EQ(m[1].feed, 100.0);
}

TEST(InterpreterArc, G2IsClockwiseNegativeRotation) {
  const auto m = run_lines({"G0 X0 Y10", "G2 X10 Y0 J-10 F100"});  // I omitted = 0
  EXPECT_EQ(m[1].rotation, -1);
  expect_near(m[1].center, {0, 0, 0});
}

TEST(InterpreterArc, AbsoluteCentreModeG901) {
  const auto m = run_lines({"G0 X10 Y5", "G90.1 G3 X0 Y15 I0 J5 F100"});
  expect_near(m[1].center, {0, 5, 0});
  // Back to incremental centres.
  const auto n = run_lines({"G0 X10 Y5", "G90.1", "G91.1 G3 X0 Y15 I-10 J0 F100"});
  expect_near(n[1].center, {0, 5, 0});
}

TEST(InterpreterArc, AbsoluteCentreNeedsBothWords) {
  EXPECT_NE(error_of({"G0 X10", "G90.1 G3 X0 Y10 I0 F100"}).find("J word missing"),
            std::string::npos);
}

TEST(InterpreterArc, RFormShortAndLongArc) {
  // Chord 10 along +X, R 10: centre on the bisector x = 5 at distance sqrt(75).
  const double h = std::sqrt(75.0);
  const auto shortarc = run_lines({"G0 X0 Y0", "G2 X10 Y0 R10 F100"});
  expect_near(shortarc[1].center, {5, -h, 0});
  EXPECT_EQ(shortarc[1].rotation, -1);
  const auto longarc = run_lines({"G0 X0 Y0", "G2 X10 Y0 R-10 F100"});  // more than 180 degrees
  expect_near(longarc[1].center, {5, h, 0});
  const auto ccw = run_lines({"G0 X0 Y0", "G3 X10 Y0 R10 F100"});
  expect_near(ccw[1].center, {5, h, 0});
  EXPECT_EQ(ccw[1].rotation, 1);
}

TEST(InterpreterArc, G18UsesZThenXAndRotationAboutY) {
  // From (10, 0, 0) to (0, 0, 10): (first, second) = (Z, X) goes (0,10) -> (10,0).
  // G3 with R 10 (at most 180 degrees) turns counter-clockwise in (Z, X):
  // the centre is at Z = 10, X = 10.
  const auto m = run_lines({"G0 X10 Y0 Z0", "G18 G3 X0 Z10 R10 F100"});
  EXPECT_EQ(m[1].plane, Plane::xz);
  EXPECT_EQ(m[1].rotation, 1);
  expect_near(m[1].center, {10, 0, 10});
  const auto ijk = run_lines({"G0 X10 Y0 Z0", "G18 G2 X0 Z10 I-10 K0 F100"});
  expect_near(ijk[1].center, {0, 0, 0});
  EXPECT_EQ(ijk[1].rotation, -1);
}

TEST(InterpreterArc, G19UsesYThenZ) {
  // (first, second) = (Y, Z): (10,0) -> (0,10); G2 with R 10 turns clockwise:
  // centre Y = 10, Z = 10.
  const auto m = run_lines({"G0 X0 Y10 Z0", "G19 G2 Y0 Z10 R10 F100"});
  EXPECT_EQ(m[1].plane, Plane::yz);
  EXPECT_EQ(m[1].rotation, -1);
  expect_near(m[1].center, {0, 10, 10});
}

TEST(InterpreterArc, OffPlaneCentreWordIsRefused) {
  EXPECT_NE(error_of({"G0 X10", "G3 X0 Y10 I-10 K1 F100"})
                .find("K word given for an arc in the XY plane"),
            std::string::npos);
  EXPECT_NE(error_of({"G0 X10", "G18 G3 X0 Z10 I-10 J1 F100"}).find("J word given"),
            std::string::npos);
  EXPECT_NE(error_of({"G0 Y10", "G19 G3 Y0 Z10 J-10 I1 F100"}).find("I word given"),
            std::string::npos);
}

TEST(InterpreterArc, TurnsAndFullCircle) {
  const auto m = run_lines({"G0 X10 Y0", "G3 X10 Y0 I-10 J0 P3 F100"});
  EXPECT_EQ(m[1].rotation, 3);
  expect_near(m[1].center, {0, 0, 0});
  const auto full = run_lines({"G2 I5 F100"});  // no end point: one full circle (IJK form)
  ASSERT_EQ(full.size(), 1u);
  EXPECT_EQ(full[0].rotation, -1);
  expect_near(full[0].start, full[0].end);
  expect_near(full[0].center, {5, 0, 0});
  EXPECT_NE(error_of({"G2 X1 I1 P0 F1"}).find("1 or more"), std::string::npos);
  EXPECT_NE(error_of({"G2 X2 I1 P1.5 F1"}).find("not an integer"), std::string::npos);
}

TEST(InterpreterArc, HelixMovesTheNormalAxisLinearly) {
  const auto m = run_lines({"G0 X10 Y0 Z0", "G3 X0 Y10 Z5 I-10 J0 F100"});
  expect_near(m[1].end, {0, 10, 5});
  expect_near(m[1].center, {0, 0, 0});  // centre at the start's Z
  const auto g18 = run_lines({"G0 X10 Y3 Z0", "G18 G3 X0 Y7 Z10 R10 F100"});
  expect_near(g18[1].center, {10, 3, 10});
  expect_near(g18[1].end, {0, 7, 10});
}

TEST(InterpreterArc, InchArcIsConvertedToMm) {
  const auto m = run_lines({"G20 G0 X1 Y0", "G3 X0 Y1 I-1 J0 F10"});
  expect_near(m[1].end, {0, 25.4, 0});
  expect_near(m[1].center, {0, 0, 0});
  EXPECT_NEAR(m[1].feed, 254.0, 1e-9);
}

TEST(InterpreterArc, RadiusMismatchUsesLinuxCncTolerances) {
  // Absolute tolerance 0.028284 mm AND relative 0.1 % must both be exceeded...
  EXPECT_EQ(error_of({"G0 X100", "G3 X0 Y100.05 I-100 J0 F100"}), "");  // 0.05 mm, 0.05 %
  EXPECT_NE(error_of({"G0 X10", "G3 X0 Y10.03 I-10 J0 F100"}).find("arc radius mismatch"),
            std::string::npos);                                      // 0.03 mm, 0.3 %
  EXPECT_EQ(error_of({"G0 X10", "G3 X0 Y10.02 I-10 J0 F100"}), "");  // 0.02 mm < abs tol
  // ... unless beyond the hard cap of 100 x 0.028284 mm.
  EXPECT_EQ(error_of({"G0 X10000", "G3 X0 Y10002.7 I-10000 J0 F100"}), "");
  EXPECT_NE(error_of({"G0 X10000", "G3 X0 Y10002.9 I-10000 J0 F100"}).find("arc radius mismatch"),
            std::string::npos);
  // Inch: 0.0028284 in.
  EXPECT_EQ(error_of({"G20 G0 X1", "G3 X0 Y1.002 I-1 J0 F10"}), "");
  EXPECT_NE(error_of({"G20 G0 X1", "G3 X0 Y1.003 I-1 J0 F10"}).find("mismatch"), std::string::npos);
}

TEST(InterpreterArc, ImpossibleAndDegenerateRArcs) {
  EXPECT_NE(error_of({"G2 X10 Y0 R4 F100"}).find("impossible R arc"), std::string::npos);
  EXPECT_EQ(error_of({"G2 X10 Y0 R4.999 F100"}), "");  // 0.001 mm short: within 0.00127 mm
  EXPECT_NE(error_of({"G0 X1", "G2 X1 Y0 R5 F100"}).find("zero chord"), std::string::npos);
  EXPECT_NE(error_of({"G2 R5 F100"}).find("arc with no end point"), std::string::npos);
  EXPECT_NE(error_of({"G2 Z5 R5 F100"}).find("arc with no end point"), std::string::npos);
  EXPECT_NE(error_of({"G2 X5 F100"}).find("without I, J, K or R"), std::string::npos);
  EXPECT_NE(error_of({"G2 X5 R5 I2 F100"}).find("both R and I/J/K"), std::string::npos);
  EXPECT_NE(error_of({"G2 X5 R5"}).find("zero feed rate"), std::string::npos);
  EXPECT_NE(error_of({"G2 X0.0001 R0 F100"}).find("zero-radius arc"), std::string::npos);
}

TEST(InterpreterArc, ErrorNamesFileLineAndColumn) {
  const std::string e = error_of({"G0 X10", "G3 X0 Y10.03 I-10 J0 F100"});
  EXPECT_EQ(e.rfind("test.nc:2:1: error: arc radius mismatch", 0), 0u) << e;
}

}  // namespace
}  // namespace abbe::gcode
