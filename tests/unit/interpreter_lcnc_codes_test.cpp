// LinuxCNC codes without geometry of their own (issue 13): M48-M53
// overrides, M61 Q (tool in the spindle), G43.1 (dynamic tool length),
// M70-M73 (save / invalidate / restore the modal state) and polar
// coordinates @ ^. Every expected value is worked out by hand from
// rs274ngc's rules (checked with LinuxCNC 2.9's rs274, docs/interop.md).
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "abbe/gcode/program.hpp"
#include "abbe/io/input_error.hpp"
#include "test_blocks.hpp"

namespace abbe::gcode {
namespace {

using testing::run_lines;

std::vector<Motion> run(const std::string& program, const InterpreterConfig& config = {}) {
  std::istringstream in(program);
  std::vector<Motion> out;
  run_program(in, "t.ngc", config, [&](const Motion& m) { out.push_back(m); });
  return out;
}

std::string error_of(const std::string& program, const InterpreterConfig& config = {}) {
  try {
    run(program, config);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

void expect_end(const Motion& m, double x, double y, double z) {
  EXPECT_NEAR(m.end.x(), x, 1e-9) << m.line;
  EXPECT_NEAR(m.end.y(), y, 1e-9) << m.line;
  EXPECT_NEAR(m.end.z(), z, 1e-9) << m.line;
}

TEST(LinuxCncCodes, OverridesAreCarriedWithoutMotion) {
  const auto m = run("G0 X1\nM50 P0\nM51 P1\nM52 P1\nM53 P1\nM48\nM49\nG0 X2\n");
  ASSERT_EQ(m.size(), 2u);
  expect_end(m[0], 1, 0, 0);
  expect_end(m[1], 2, 0, 0);
  // One override code per block, as rs274ngc (modal group 9).
  EXPECT_NE(error_of("M48 M50\n").find("two M codes of the same modal group"), std::string::npos);
  // P belongs to M50-M53 only.
  EXPECT_NE(error_of("M48 P1\n").find("P word with no"), std::string::npos);
}

TEST(LinuxCncCodes, M61SetsTheToolThatG43Uses) {
  InterpreterConfig config;
  config.tool_lengths[3] = 10.0;
  config.tool_lengths[5] = 4.0;
  // G43 without H: the tool in the spindle (3). The spindle stays where it
  // is (tip = nose - 10 mm), a move to Z0 puts the tip at Z0.
  const auto m = run("T5\nM61 Q3\nG43\nG0 X1\nG0 Z0\n", config);
  ASSERT_EQ(m.size(), 2u);
  expect_end(m[0], 1, 0, -10);
  expect_end(m[1], 1, 0, 0);
  EXPECT_DOUBLE_EQ(m[1].tool_length, 10.0);
  EXPECT_EQ(m[1].tool, 3);
  EXPECT_NE(error_of("M61\n").find("M61 needs a non-negative Q word"), std::string::npos);
  EXPECT_NE(error_of("M61 Q-1\n").find("M61 needs a non-negative Q word"), std::string::npos);
  EXPECT_NE(error_of("M61 Q1.5\n").find("not an integer"), std::string::npos);
  EXPECT_NE(error_of("T1 M6 M61 Q1\n").find("two M codes of the same modal group"),
            std::string::npos);
}

TEST(LinuxCncCodes, G43_1TakesTheToolLengthFromZ) {
  // G43.1 Z5: the tip is 5 mm below the spindle nose; the nose does not move.
  const auto m = run("G43.1 Z5\nG0 X1\nG0 Z0\nG49\nG0 X2\n");
  ASSERT_EQ(m.size(), 3u);
  expect_end(m[0], 1, 0, -5);
  EXPECT_DOUBLE_EQ(m[0].tool_length, 5.0);
  expect_end(m[1], 1, 0, 0);
  // G49: the offset goes, the nose stays (5 mm above the old tip).
  expect_end(m[2], 2, 0, 5);
  EXPECT_DOUBLE_EQ(m[2].tool_length, 0.0);
  // In inches the Z word is inches; G43.1 in a G1 block of its own makes no move.
  const auto inch = run("G1 X0 F10\nG20 G43.1 Z1\nG0 X0\n");
  ASSERT_EQ(inch.size(), 2u);
  expect_end(inch[1], 0, 0, -25.4);
  EXPECT_NEAR(inch[1].tool_length, 25.4, 1e-12);
  EXPECT_NE(error_of("G43.1 X1\n").find("a tool offset along X (G43.1 X) is not supported"),
            std::string::npos);
  EXPECT_NE(error_of("G1 X1 F1 G43.1 Z1\n").find("both use axis words (G1 and G43.1)"),
            std::string::npos);
  EXPECT_NE(error_of("G92 X1 G43.1 Z1\n").find("both use axis words (G43.1 and G92)"),
            std::string::npos);
}

TEST(LinuxCncCodes, G43_2AddsToTheToolLengthOffset) {
  // rs274 (LinuxCNC 2.9): G43.1 Z3 then G43.2 H1 with tool 1 = 12.7 mm
  // gives USE_TOOL_LENGTH_OFFSET(0 0 15.7); G49 clears both.
  InterpreterConfig config;
  config.tool_lengths[1] = 12.7;
  const auto m = run("G21 G43.1 Z3\nG43.2 H1\nG0 X1\nG43.2 Z0.3\nG0 X2\nG49\nG0 X3\n", config);
  ASSERT_EQ(m.size(), 3u);
  expect_end(m[0], 1, 0, -15.7);
  EXPECT_NEAR(m[0].tool_length, 15.7, 1e-12);
  expect_end(m[1], 2, 0, -16.0);
  EXPECT_NEAR(m[1].tool_length, 16.0, 1e-12);
  expect_end(m[2], 3, 0, 0);
  // Without G43 in force it adds to nothing; G20: the Z word is inches.
  const auto inch = run("G20 G43.2 Z1\nG0 X0\n", config);
  ASSERT_EQ(inch.size(), 1u);
  EXPECT_NEAR(inch[0].tool_length, 25.4, 1e-12);
  EXPECT_NE(error_of("G43.2\n").find("G43.2 needs an H word (a tool) or a Z word"),
            std::string::npos);
  EXPECT_NE(error_of("G43.2 H1 Z1\n", config).find("both an H word and axis words"),
            std::string::npos);
  EXPECT_NE(error_of("G43.2 X1\n").find("a tool offset along X (G43.2 X)"), std::string::npos);
  EXPECT_NE(error_of("G43.2 H7\n").find("tool 7 has no length in the tool table"),
            std::string::npos);
}

TEST(LinuxCncCodes, M70SavesAndM72RestoresTheModes) {
  // Saved: mm, G90, F100. Changed to inch, G91, F5 (after G20: an F in the
  // block of G20 is still read in mm, as rs274ngc does): X1 is 25.4 mm at
  // 127 mm/min. Restored: X1 is absolute 1 mm at 100 mm/min.
  const auto m = run("G21 G90 G0 X0 F100\nM70\nG20 G91\nF5\nG1 X1\nM72\nG1 X1\n");
  ASSERT_EQ(m.size(), 3u);
  expect_end(m[1], 25.4, 0, 0);
  EXPECT_NEAR(m[1].feed, 127.0, 1e-9);
  expect_end(m[2], 1, 0, 0);
  EXPECT_NEAR(m[2].feed, 100.0, 1e-9);
  // M72 restores again and again (M71 invalidates).
  const auto twice = run("G90 F100\nM70\nG91\nG0 X1\nM72\nG0 X1\nG91\nM72\nG0 X1\n");
  ASSERT_EQ(twice.size(), 3u);
  expect_end(twice[2], 1, 0, 0);
  // The work offset comes back: G55 saved, G54 set, G55 restored.
  InterpreterConfig config;
  config.work_offsets[1] = {10, 20, 30};
  const auto frame = run("G55\nM70\nG54\nG0 X1\nM72\nG0 X1\n", config);
  ASSERT_EQ(frame.size(), 2u);
  expect_end(frame[0], 1, 0, 0);
  expect_end(frame[1], 11, 0, 0);  // Y, Z not written: stay where they are
  // G43 comes back with the tool in the spindle (rs274ngc re-executes G43).
  config.tool_lengths[2] = 7.0;
  const auto tool = run("T2 M6\nG43\nM70\nG49\nM72\nG0 Z0\n", config);
  ASSERT_EQ(tool.size(), 1u);
  EXPECT_DOUBLE_EQ(tool[0].tool_length, 7.0);
  expect_end(tool[0], 0, 0, 0);
  // The motion mode is not part of the saved state (rs274ngc).
  EXPECT_NE(error_of("G0 X0\nM70\nG1 X1 F10\nM72\nX2\n").find("zero feed rate"), std::string::npos);
}

TEST(LinuxCncCodes, M72NeedsAStateOfItsCallLevel) {
  EXPECT_NE(error_of("G0 X0\nM72\n").find("M72 without a state saved by M70 or M73"),
            std::string::npos);
  EXPECT_NE(error_of("M70\nM71\nM72\n").find("M72 without a state saved"), std::string::npos);
  // A state saved in a subroutine belongs to its call.
  EXPECT_NE(error_of("o<a> sub\nM70\no<a> endsub\no<a> call\nM72\n").find("M72 without"),
            std::string::npos);
  EXPECT_NE(error_of("M70\no<a> sub\nM72\no<a> endsub\no<a> call\n").find("M72 without"),
            std::string::npos);
  const std::string e = error_of("G0 X0\nM72\n");
  EXPECT_NE(e.find("t.ngc:2:1:"), std::string::npos) << e;
}

TEST(LinuxCncCodes, M73RestoresAtTheReturn) {
  const std::string program =
      "o<s> sub\nM73\nG20 G91\nF5\nG1 X1\no<s> endsub\n"
      "G21 G90 G1 X0 F100\no<s> call\nG1 X2\n"
      "o<r> sub\nM73\nG91 F7\no<r> return\no<r> endsub\no<r> call\nG1 X3\nM2\n";
  const auto m = run(program);
  ASSERT_EQ(m.size(), 4u);
  expect_end(m[1], 25.4, 0, 0);
  EXPECT_NEAR(m[1].feed, 127.0, 1e-9);
  expect_end(m[2], 2, 0, 0);  // mm, G90, F100 again
  EXPECT_NEAR(m[2].feed, 100.0, 1e-9);
  expect_end(m[3], 3, 0, 0);  // restored by return as well
  EXPECT_NEAR(m[3].feed, 100.0, 1e-9);
}

TEST(LinuxCncCodes, PolarCoordinates) {
  // Values from the rules (and as rs274 prints them): G90 @ and ^ about the
  // program origin, the missing one the current point's; G91 both add.
  const auto m =
      run("G0 X1 Y1 Z0\nG0 @2 ^30\nG0 @1\nG0 ^90\nG91 G0 @1 ^90\nG0 @1\nG0 ^45\n"
          "G90 G0 X3 Y4\nG0 ^10\n");
  ASSERT_EQ(m.size(), 9u);
  const double s3 = std::sqrt(3.0);
  expect_end(m[1], s3, 1, 0);
  expect_end(m[2], s3 / 2, 0.5, 0);
  expect_end(m[3], 0, 1, 0);
  expect_end(m[4], -2, 0, 0);  // r 1+1, angle 90+90
  expect_end(m[5], -3, 0, 0);
  expect_end(m[6], -3 / std::sqrt(2.0), -3 / std::sqrt(2.0), 0);
  expect_end(m[8], 5 * std::cos(10 * M_PI / 180), 5 * std::sin(10 * M_PI / 180), 0);
  // An arc to a polar end point, with Z.
  const auto arc = run("G0 @2 ^30 Z5 F100\nG1 @3 ^30\nG2 @3 ^60 R3\n");
  ASSERT_EQ(arc.size(), 3u);
  expect_end(arc[2], 1.5, 1.5 * s3, 5);
  EXPECT_EQ(arc[2].kind, MotionKind::arc);

  EXPECT_NE(error_of("G0 @2 ^30 X1\n").find("both polar coordinates (@, ^) and an X word"),
            std::string::npos);
  EXPECT_NE(error_of("G91 G0 @1\n").find("indeterminate at the origin"), std::string::npos);
  EXPECT_NE(error_of("G92 @1 ^0\n").find("can only be used for motion"), std::string::npos);
  EXPECT_NE(error_of("G18 G81 @2 ^0 R1 F10\n").find("with a canned cycle in the XZ plane"),
            std::string::npos);
  // Canned cycles: G90 holes from the polar words; G91 turns each repeat
  // about the origin (six holes 60° apart on a circle of radius 1.5).
  // (G99: up to R where the tool stands, then per hole over it at R, down, up.)
  const auto holes = run("G0 X1.5 Y0 Z0\nG91 G81 R.1 Z-.5 ^60 L6 F10\n");
  ASSERT_EQ(holes.size(), 2u + 6u * 3u);
  for (int k = 0; k < 6; ++k) {
    const double a = (k + 1) * M_PI / 3.0;
    expect_end(holes[static_cast<std::size_t>(2 + 3 * k)], 1.5 * std::cos(a), 1.5 * std::sin(a),
               0.1);
  }
  const auto bolt = run("G0 X2.5 Y0 Z1\nG81 R.1 Z-0.5 F60\n^120\n");
  ASSERT_EQ(bolt.size(), 8u);
  expect_end(bolt[5], 2.5 * std::cos(2 * M_PI / 3), 2.5 * std::sin(2 * M_PI / 3), 0.1);
  const std::string e = error_of("G0 X0\nG0 @1 ^0 Y2\n");
  EXPECT_NE(e.find("t.ngc:2:10:"), std::string::npos) << e;
}

TEST(LinuxCncCodes, LineByLineCommandsRefusePolarWords) {
  // Interpreter::execute (compensate, verify rewrite X and Y words line by line).
  try {
    run_lines({"G0 @1 ^0"});
    FAIL() << "polar words accepted line by line";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("polar coordinates (@, ^) are not supported by a command"),
              std::string::npos);
  }
}

}  // namespace
}  // namespace abbe::gcode

namespace abbe::gcode {
namespace {

// Cutter radius compensation: tool-centre paths worked out by hand (the
// same programs give the same numbers in LinuxCNC's rs274).
std::vector<Motion> comp_run(const std::string& program) {
  InterpreterConfig config;
  config.tool_diameters[1] = 4.0;
  return run(program, config);
}

void expect_xy(const Motion& m, double x, double y) {
  EXPECT_NEAR(m.end.x(), x, 1e-9) << "line " << m.line;
  EXPECT_NEAR(m.end.y(), y, 1e-9) << "line " << m.line;
}

TEST(CutterComp, SquareOutsideWithG41) {
  // A clockwise 10 mm square, tool (radius 2) on the left = outside. Entry
  // from (-10,-10) to (0,0): the end is offset perpendicular to the entry
  // move, (-√2, √2); the inside corner with the first side puts it where
  // the offset lines meet, (-2, 2·tan 22.5°). Outside corners: arcs of
  // radius 2 about the programmed corners (clockwise).
  const auto m = comp_run(
      "G21 G0 X-10 Y-10 Z0 F100\nT1 M6\nG41 G1 X0 Y0\nY10\nX10\nY0\nX0\nG40 G1 X-10 Y-10\nM2\n");
  ASSERT_EQ(m.size(), 10u);
  const double t = 2.0 * (std::sqrt(2.0) - 1.0);
  expect_xy(m[1], -2, t);
  EXPECT_EQ(m[1].line, 3u);
  EXPECT_EQ(m[1].kind, MotionKind::linear);
  expect_xy(m[2], -2, 10);
  EXPECT_EQ(m[3].kind, MotionKind::arc);
  expect_xy(m[3], 0, 12);
  EXPECT_NEAR(m[3].center.x(), 0, 1e-12);
  EXPECT_NEAR(m[3].center.y(), 10, 1e-12);
  EXPECT_EQ(m[3].rotation, -1);
  EXPECT_EQ(m[3].line, 5u);  // the corner belongs to the move after it
  expect_xy(m[4], 10, 12);
  expect_xy(m[5], 12, 10);
  expect_xy(m[6], 12, 0);
  expect_xy(m[7], 10, -2);
  expect_xy(m[8], 0, -2);
  expect_xy(m[9], -10, -10);  // G40: the exit move ends at the programmed point
  // Every motion starts where the previous one ended (the tool centre path).
  for (std::size_t i = 1; i < m.size(); ++i)
    EXPECT_NEAR((m[i].start - m[i - 1].end).norm(), 0.0, 1e-12) << i;
}

TEST(CutterComp, SquareInsideWithG42) {
  // The same square with G42.1 D4 (right = inside): an outside corner at the
  // entry (arc about (0,0)), then inside corners at the intersections 2 mm
  // in from each side.
  const auto m =
      run("G21 G0 X-10 Y-10 Z0 F100\nG42.1 D4 G1 X0 Y0\nY10\nX10\nY0\nX0\nG40 X-10 Y-10\n");
  ASSERT_EQ(m.size(), 8u);
  expect_xy(m[1], std::sqrt(2.0), -std::sqrt(2.0));
  EXPECT_EQ(m[2].kind, MotionKind::arc);
  EXPECT_EQ(m[2].rotation, 1);
  expect_xy(m[2], 2, 0);
  expect_xy(m[3], 2, 8);
  expect_xy(m[4], 8, 8);
  expect_xy(m[5], 8, 2);
  expect_xy(m[6], 0, 2);
  expect_xy(m[7], -10, -10);
  EXPECT_NEAR((m[7].start - m[6].end).norm(), 0.0, 1e-12);  // the exit starts at the tool
}

TEST(CutterComp, ArcsAreOffsetByTheRadius) {
  // Up to (0,0), then a G3 half circle of radius 5 about (5,0) (it starts
  // downwards: a reversal), then down. Tool radius 2 on the left = inside
  // the arc: the centre path is the concentric arc of radius 3; each
  // reversal is a half-circle corner arc about the programmed corner.
  const auto m = run("G0 X0 Y-10 F100\nG41.1 D4 G1 X0 Y0\nG3 X10 Y0 I5 J0\nG1 Y-10\nG40 G0 X20\n");
  ASSERT_EQ(m.size(), 7u);
  expect_xy(m[1], -2, 0);  // entry: 2 mm to the left of the upward move
  EXPECT_EQ(m[2].kind, MotionKind::arc);
  expect_xy(m[2], 2, 0);
  EXPECT_NEAR(m[2].center.x(), 0, 1e-12);
  EXPECT_EQ(m[2].rotation, -1);
  EXPECT_EQ(m[3].kind, MotionKind::arc);
  expect_xy(m[3], 8, 0);
  EXPECT_NEAR(m[3].center.x(), 5, 1e-12);
  EXPECT_EQ(m[3].rotation, 1);
  EXPECT_NEAR((m[3].start - m[3].center).norm(), 3.0, 1e-9);
  EXPECT_NEAR((m[3].end - m[3].center).norm(), 3.0, 1e-9);
  expect_xy(m[4], 12, 0);
  EXPECT_NEAR(m[4].center.x(), 10, 1e-12);
  expect_xy(m[5], 12, -10);
  expect_xy(m[6], 20, -10);
  EXPECT_EQ(m[6].kind, MotionKind::rapid);
}

TEST(CutterComp, ImpossibleGeometryIsAnErrorAtItsLine) {
  InterpreterConfig config;
  config.tool_diameters[1] = 4.0;
  // Entry move not longer than the radius.
  EXPECT_NE(error_of("G0 X0 Y0\nG41.1 D4 G1 X1 F10\n").find("t.ngc:2:"), std::string::npos);
  EXPECT_NE(error_of("G0 X0 Y0\nG41.1 D4 G1 X1 F10\n").find("not longer than the tool radius"),
            std::string::npos);
  // The tool inside an arc smaller than itself.
  EXPECT_NE(error_of("G0 X0 Y-10 F1\nG41.1 D4 G1 X0 Y0\nG3 X2 Y0 I1\n")
                .find("is not less than the arc radius"),
            std::string::npos);
  // An inside corner the tool cannot reach: a 1 mm step with a 2 mm radius.
  const std::string step = error_of("G0 X-10 Y-10 F1\nG42.1 D4 G1 X0 Y0\nY10\nX1\nY0\nX5\nM2\n");
  EXPECT_NE(step.find("straight feed in concave corner cannot be reached by the tool without "
                      "gouging"),
            std::string::npos)
      << step;
  EXPECT_NE(step.find("t.ngc:5:"), std::string::npos) << step;
  EXPECT_NE(error_of("G18\nG41.1 D4 L1\n").find("lathe tool orientation"), std::string::npos);
  EXPECT_NE(error_of("G19\nG41.1 D4\n").find("only in the XY or XZ plane"), std::string::npos);
  EXPECT_NE(error_of("G41.1 D4\nG42.1 D4\n").find("when it is on"), std::string::npos);
  EXPECT_NE(error_of("G41.1\n").find("G41.1 with no D word"), std::string::npos);
  EXPECT_NE(error_of("G41 D3\n", config).find("(G41 D3): tool 3 has no diameter in the tool table"),
            std::string::npos);
  EXPECT_NE(error_of("G41\n", config).find("without a tool in the spindle"), std::string::npos);
  EXPECT_NE(error_of("G41.1 D4\nG20\n").find("G20 while cutter radius compensation is on"),
            std::string::npos);
  EXPECT_NE(error_of("G41.1 D4\nG0 X10\nG81 X0 Y0 Z-1 R1\n").find("G81 while cutter radius"),
            std::string::npos);
  EXPECT_NE(error_of("G0 X-9 F1\nG41.1 D4 G1 X0\nG40\nG2 X1 Y1 R1\n").find("must be straight"),
            std::string::npos);
  EXPECT_NE(error_of("G0 X-9\nG41.1 D4 G2 X-8 Y0 R5 F1\n").find("entry arc is not greater"),
            std::string::npos);
  EXPECT_NE(error_of("D1\n").find("D word with no"), std::string::npos);
}

TEST(CutterComp, XZPlaneWorksInZAndX) {
  // G18: compensation works in the plane's axes (Z, X). A move along +Z
  // is (1, 0) there; its left, turned by +90°, is (0, 1): +X. Tool radius 2.
  const auto m = run("G18 G0 X0 Y0 Z-10 F100\nG41.1 D4 G1 Z0\nZ10\nG40 G0 Z20\n");
  ASSERT_EQ(m.size(), 4u);
  EXPECT_NEAR(m[1].end.x(), 2.0, 1e-12);
  EXPECT_NEAR(m[1].end.z(), 0.0, 1e-12);
  EXPECT_NEAR(m[2].end.x(), 2.0, 1e-12);
  EXPECT_NEAR(m[2].end.z(), 10.0, 1e-12);
  EXPECT_NEAR(m[3].end.x(), 0.0, 1e-12);
}

TEST(CutterComp, QueuedMotionsComeOutAtTheEnd) {
  // Without G40 or M2 the last compensated move is still handed on.
  const auto m = run("G0 X-10 Y0 F100\nG41.1 D2 G1 X0\nX10\n");
  ASSERT_EQ(m.size(), 3u);
  expect_xy(m[1], 0, 1);
  expect_xy(m[2], 10, 1);
  EXPECT_EQ(m[2].line, 3u);
  // A dwell between compensated moves keeps its place.
  const auto d = run("G0 X-10 Y0 F100\nG41.1 D2 G1 X0\nG4 P1\nX10\nM2\n");
  ASSERT_EQ(d.size(), 4u);
  EXPECT_EQ(d[2].kind, MotionKind::dwell);
  EXPECT_EQ(d[2].line, 3u);
  expect_xy(d[2], 0, 1);
  // G41.1 with a zero diameter changes nothing.
  const auto z = run("G0 X-10 Y0 F100\nG41.1 D0 G1 X0\nX10\n");
  ASSERT_EQ(z.size(), 3u);
  expect_xy(z[1], 0, 0);
}

TEST(CutterComp, LineByLineCommandsRefuseIt) {
  try {
    run_lines({"G41.1 D4"});
    FAIL() << "cutter compensation accepted line by line";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("rewrites the program line by line"), std::string::npos);
  }
}

}  // namespace
}  // namespace abbe::gcode
