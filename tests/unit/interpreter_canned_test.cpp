// Canned cycles G73, G81, G82, G83, G85, G89 with G98/G99, L repeats (G90 and
// G91), other planes, and their errors. Expected moves are worked out by hand
// from the rs274ngc rules (initial level, R plane, clearance).
#include <gtest/gtest.h>

#include "interpreter_checks.hpp"
#include "test_blocks.hpp"

namespace abbe::gcode {
namespace {

using testing::error_of;
using testing::run_lines;

struct Expected {
  MotionKind kind;
  Eigen::Vector3d end;
  double dwell = 0.0;
};

const auto R = MotionKind::rapid;
const auto F = MotionKind::linear;
const auto D = MotionKind::dwell;

// Compares the motions of the last block (line `line`) with `expected`.
void expect_moves(const std::vector<Motion>& all, std::size_t line,
                  const std::vector<Expected>& expected) {
  std::vector<Motion> m;
  for (const auto& x : all)
    if (x.line == line) m.push_back(x);
  ASSERT_EQ(m.size(), expected.size());
  Eigen::Vector3d previous = m.front().start;
  for (std::size_t i = 0; i < m.size(); ++i) {
    EXPECT_EQ(m[i].kind, expected[i].kind) << "move " << i;
    EXPECT_NEAR((m[i].end - expected[i].end).norm(), 0.0, 1e-9)
        << "move " << i << ": " << m[i].end.transpose() << " expected "
        << expected[i].end.transpose();
    EXPECT_NEAR((m[i].start - previous).norm(), 0.0, 1e-9) << "move " << i << " is not continuous";
    EXPECT_EQ(m[i].sub, i);
    if (expected[i].kind == D) {
      EXPECT_DOUBLE_EQ(m[i].dwell_seconds, expected[i].dwell);
    }
    if (expected[i].kind == F) {
      EXPECT_DOUBLE_EQ(m[i].feed, 100.0);
    }
    previous = m[i].end;
  }
}

TEST(InterpreterCanned, G81RetractG98AndG99) {
  const auto g98 = run_lines({"G0 X0 Y0 Z10 F100", "G98 G81 X5 Y5 Z-1 R2"});
  expect_moves(g98, 2, {{R, {5, 5, 10}}, {R, {5, 5, 2}}, {F, {5, 5, -1}}, {R, {5, 5, 10}}});
  // G99 is the start-up retract mode (as in rs274ngc).
  const auto g99 = run_lines({"G0 X0 Y0 Z10 F100", "G81 X5 Y5 Z-1 R2", "X6"});
  expect_moves(g99, 2, {{R, {5, 5, 10}}, {R, {5, 5, 2}}, {F, {5, 5, -1}}, {R, {5, 5, 2}}});
  expect_moves(g99, 3, {{R, {6, 5, 2}}, {F, {6, 5, -1}}, {R, {6, 5, 2}}});
}

TEST(InterpreterCanned, G98ReturnsToTheLevelWhereTheSeriesStarted) {
  const auto m = run_lines({"G0 X0 Y0 Z10 F100", "G99 G81 X1 Z-1 R1", "G98 X2"});
  // The second hole starts at R (1) but returns to the initial level 10.
  expect_moves(m, 3, {{R, {2, 0, 10}}, {R, {2, 0, 1}}, {F, {2, 0, -1}}, {R, {2, 0, 10}}});
}

TEST(InterpreterCanned, StartBelowRPlaneRisesFirst) {
  const auto m = run_lines({"G0 X2 Y0 Z0.5 F100", "G98 G81 X3 Z-1 R1"});
  expect_moves(m, 2, {{R, {2, 0, 1}}, {R, {3, 0, 1}}, {F, {3, 0, -1}}, {R, {3, 0, 1}}});
}

TEST(InterpreterCanned, G82Dwells) {
  const auto m = run_lines({"G0 Z10 F100", "G98 G82 X3 Y1 Z-1 R2 P0.25"});
  expect_moves(
      m, 2,
      {{R, {3, 1, 10}}, {R, {3, 1, 2}}, {F, {3, 1, -1}}, {D, {3, 1, -1}, 0.25}, {R, {3, 1, 10}}});
  const auto g99 = run_lines({"G0 Z10 F100", "G99 G82 X3 Y1 Z-1 R2 P0.25"});
  expect_moves(
      g99, 2,
      {{R, {3, 1, 10}}, {R, {3, 1, 2}}, {F, {3, 1, -1}}, {D, {3, 1, -1}, 0.25}, {R, {3, 1, 2}}});
}

TEST(InterpreterCanned, G85FeedsOutToRThenRapidsToClearance) {
  const auto m = run_lines({"G0 Z10 F100", "G98 G85 X1 Y1 Z-1 R2"});
  expect_moves(m, 2,
               {{R, {1, 1, 10}}, {R, {1, 1, 2}}, {F, {1, 1, -1}}, {F, {1, 1, 2}}, {R, {1, 1, 10}}});
  const auto g99 = run_lines({"G0 Z10 F100", "G99 G85 X1 Y1 Z-1 R2"});
  expect_moves(g99, 2,
               {{R, {1, 1, 10}}, {R, {1, 1, 2}}, {F, {1, 1, -1}}, {F, {1, 1, 2}}, {R, {1, 1, 2}}});
}

TEST(InterpreterCanned, G89DwellsAndFeedsOutToClearance) {
  const auto m = run_lines({"G0 Z10 F100", "G98 G89 X2 Y1 Z-1 R2 P0.5"});
  expect_moves(
      m, 2,
      {{R, {2, 1, 10}}, {R, {2, 1, 2}}, {F, {2, 1, -1}}, {D, {2, 1, -1}, 0.5}, {F, {2, 1, 10}}});
  const auto g99 = run_lines({"G0 Z10 F100", "G99 G89 X2 Y1 Z-1 R2 P0.5"});
  expect_moves(
      g99, 2,
      {{R, {2, 1, 10}}, {R, {2, 1, 2}}, {F, {2, 1, -1}}, {D, {2, 1, -1}, 0.5}, {F, {2, 1, 2}}});
}

TEST(InterpreterCanned, G83PecksOutToRAndBackDown) {
  // R 1, Q 0.8, bottom -2: pecks at 0.2, -0.6, -1.4, then -2; back down to
  // 0.254 mm above the previous depth.
  std::vector<Expected> pecks = {{R, {0, 0, 3}}, {R, {0, 0, 1}},      {F, {0, 0, 0.2}},
                                 {R, {0, 0, 1}}, {R, {0, 0, 0.454}},  {F, {0, 0, -0.6}},
                                 {R, {0, 0, 1}}, {R, {0, 0, -0.346}}, {F, {0, 0, -1.4}},
                                 {R, {0, 0, 1}}, {R, {0, 0, -1.146}}, {F, {0, 0, -2}},
                                 {R, {0, 0, 1}}};
  expect_moves(run_lines({"G0 Z3 F100", "G99 G83 X0 Y0 Z-2 R1 Q0.8"}), 2, pecks);
  // G98: the pecks still retract to R; only the last retract goes to the initial level.
  pecks.back() = {R, {0, 0, 3}};
  expect_moves(run_lines({"G0 Z3 F100", "G98 G83 X0 Y0 Z-2 R1 Q0.8"}), 2, pecks);
}

TEST(InterpreterCanned, G87BacksBoresThroughTheShift) {
  // The moves rs274 (LinuxCNC 2.9) makes for the same blocks.
  std::vector<Expected> bore = {{R, {1, 1, 5}},       {R, {1, 1, 2}},       {R, {1.5, 1.25, 2}},
                                {R, {1.5, 1.25, -1}}, {R, {1, 1, -1}},      {F, {1, 1, -0.5}},
                                {F, {1, 1, -1}},      {R, {1.5, 1.25, -1}}, {R, {1.5, 1.25, 2}},
                                {R, {1, 1, 2}}};
  const std::string start = "G0 X0 Y0 Z5 F100 S1000 M3";
  expect_moves(run_lines({start, "G99 G87 X1 Y1 Z-1 R2 I0.5 J0.25 K-0.5"}), 2, bore);
  // G98: out to the initial level.
  bore[8] = {R, {1.5, 1.25, 5}};
  bore[9] = {R, {1, 1, 5}};
  expect_moves(run_lines({start, "G98 G87 X1 Y1 Z-1 R2 I0.5 J0.25 K-0.5"}), 2, bore);
  // G91 with L2: K is taken from the bottom; the second hole from R.
  const auto inc = run_lines({start, "G91 G99 G87 X1 Y1 Z-3 R-3 I0.5 J0.25 K1 L2"});
  expect_moves(inc, 2,
               {{R, {1, 1, 5}},
                {R, {1, 1, 2}},
                {R, {1.5, 1.25, 2}},
                {R, {1.5, 1.25, -1}},
                {R, {1, 1, -1}},
                {F, {1, 1, 0}},
                {F, {1, 1, -1}},
                {R, {1.5, 1.25, -1}},
                {R, {1.5, 1.25, 2}},
                {R, {1, 1, 2}},
                {R, {2, 2, 2}},
                {R, {2.5, 2.25, 2}},
                {R, {2.5, 2.25, -1}},
                {R, {2, 2, -1}},
                {F, {2, 2, 0}},
                {F, {2, 2, -1}},
                {R, {2.5, 2.25, -1}},
                {R, {2.5, 2.25, 2}},
                {R, {2, 2, 2}}});
  EXPECT_NE(error_of({start, "G87 X1 Y1 Z-1 R2 I0.5 K-0.5"}).find("J word missing for back boring"),
            std::string::npos);
  EXPECT_NE(error_of({"G0 Z5 F100", "G87 X1 Y1 Z-1 R2 I0.5 J0 K-0.5"}).find("spindle not turning"),
            std::string::npos);
  EXPECT_NE(error_of({start, "G18", "G87 X1 Y1 Z-1 R2 I0.5 J0 K-0.5"}).find("XY plane (G17) only"),
            std::string::npos);
}

TEST(InterpreterCanned, G73BacksOffOnly) {
  const auto m = run_lines({"G0 Z3 F100", "G99 G73 X1 Y0 Z-2 R1 Q0.8"});
  expect_moves(m, 2,
               {{R, {1, 0, 3}},
                {R, {1, 0, 1}},
                {F, {1, 0, 0.2}},
                {R, {1, 0, 0.454}},
                {F, {1, 0, -0.6}},
                {R, {1, 0, -0.346}},
                {F, {1, 0, -1.4}},
                {R, {1, 0, -1.146}},
                {F, {1, 0, -2}},
                {R, {1, 0, 1}}});
  const auto g98 = run_lines({"G0 Z3 F100", "G98 G73 X1 Y0 Z-2 R1 Q0.8"});
  EXPECT_NEAR((g98.back().end - Eigen::Vector3d(1, 0, 3)).norm(), 0.0, 1e-9);
}

TEST(InterpreterCanned, G83InchUsesTheInchPeckClearance) {
  const auto m = run_lines({"G20 G0 Z1 F100", "G99 G83 X0 Y0 Z-0.5 R0.1 Q0.4"});
  // Depths (in): -0.3, then -0.5; back down to -0.3 + 0.010.
  ASSERT_GE(m.size(), 7u);
  EXPECT_NEAR(m[5].end.z(), (-0.3 + 0.010) * 25.4, 1e-9);
}

TEST(InterpreterCanned, G91RepeatsStepTheHolePosition) {
  // Initial level 10: R = 10 - 7 = 3, bottom = 3 - 3 = 0.
  const auto g99 = run_lines({"G0 X0 Y0 Z10 F100", "G91 G99 G81 X1 Y1 Z-3 R-7 L3"});
  expect_moves(g99, 2,
               {{R, {1, 1, 10}},
                {R, {1, 1, 3}},
                {F, {1, 1, 0}},
                {R, {1, 1, 3}},
                {R, {2, 2, 3}},
                {F, {2, 2, 0}},
                {R, {2, 2, 3}},
                {R, {3, 3, 3}},
                {F, {3, 3, 0}},
                {R, {3, 3, 3}}});
  const auto g98 = run_lines({"G0 X0 Y0 Z10 F100", "G91 G98 G81 X1 Y1 Z-3 R-7 L2"});
  expect_moves(g98, 2,
               {{R, {1, 1, 10}},
                {R, {1, 1, 3}},
                {F, {1, 1, 0}},
                {R, {1, 1, 10}},
                {R, {2, 2, 10}},
                {R, {2, 2, 3}},
                {F, {2, 2, 0}},
                {R, {2, 2, 10}}});
}

TEST(InterpreterCanned, G90RepeatsDrillTheSameHole) {
  const auto m = run_lines({"G0 X0 Y0 Z10 F100", "G99 G81 X1 Y1 Z-1 R2 L2"});
  expect_moves(m, 2,
               {{R, {1, 1, 10}},
                {R, {1, 1, 2}},
                {F, {1, 1, -1}},
                {R, {1, 1, 2}},
                {R, {1, 1, 2}},
                {F, {1, 1, -1}},
                {R, {1, 1, 2}}});
}

TEST(InterpreterCanned, OtherPlanesDrillAlongTheNormalAxis) {
  // G18: drilling along Y.
  const auto xz = run_lines({"G0 X0 Y5 Z0 F100", "G18 G98 G81 Z1 X2 Y-1 R3"});
  expect_moves(xz, 2, {{R, {2, 5, 1}}, {R, {2, 3, 1}}, {F, {2, -1, 1}}, {R, {2, 5, 1}}});
  // G19: drilling along X.
  const auto yz = run_lines({"G0 X5 Y0 Z0 F100", "G19 G99 G81 Y1 Z2 X-1 R3"});
  expect_moves(yz, 2, {{R, {5, 1, 2}}, {R, {3, 1, 2}}, {F, {-1, 1, 2}}, {R, {3, 1, 2}}});
}

TEST(InterpreterCanned, G80CancelsAndResetsTheInitialLevel) {
  const auto m =
      run_lines({"G0 Z10 F100", "G98 G81 X1 Z-1 R1", "G80", "G0 Z5", "G98 G81 X2 Z-1 R1"});
  EXPECT_NEAR(m.back().end.z(), 5.0, 1e-9);
  EXPECT_NE(error_of({"G0 Z10 F100", "G81 X1 Z-1 R1", "G80 X2"}).find("axis words with G80"),
            std::string::npos);
}

TEST(InterpreterCanned, Errors) {
  EXPECT_NE(error_of({"G81 X1 Z-1 R1"}).find("zero feed rate"), std::string::npos);
  EXPECT_NE(error_of({"F100 G81 X1 Z-1"}).find("R plane missing"), std::string::npos);
  EXPECT_NE(
      error_of({"F100 G81 X1 R1"}).find("Z value missing for canned cycle G81 in the XY plane"),
      std::string::npos);
  EXPECT_NE(error_of({"F100 G81 X1 Z2 R1"}).find("R plane below the hole bottom"),
            std::string::npos);
  EXPECT_NE(error_of({"F100 G81 X1 Z-1 R1 L0"}).find("positive integer"), std::string::npos);
  EXPECT_NE(error_of({"F100 G82 X1 Z-1 R1"}).find("dwell time (P) missing"), std::string::npos);
  EXPECT_NE(error_of({"F100 G83 X1 Z-1 R1"}).find("peck depth (Q) missing"), std::string::npos);
  EXPECT_NE(error_of({"F100 G83 X1 Z-1 R1 Q-1"}).find("must be positive"), std::string::npos);
  EXPECT_NE(error_of({"F100 G81 X1 Z-1 R1 P1"}).find("P word with no"), std::string::npos);
}

}  // namespace
}  // namespace abbe::gcode
