// Interpreter: linear motions, units, distance modes, work offsets, G92,
// tool length (G43/G49), G53, dwell, carried words, program end, and the
// refusals of modal conflicts and unsupported constructs.
#include <gtest/gtest.h>

#include <cmath>

#include "abbe/io/input_error.hpp"
#include "interpreter_checks.hpp"
#include "test_blocks.hpp"

namespace abbe::gcode {
namespace {

using testing::error_of;
using testing::expect_near;
using testing::make_block;
using testing::run_lines;

TEST(Interpreter, RapidAndFeedWithModalMotion) {
  const auto m = run_lines({"G0 X1 Y2 Z3", "G1 X4 F200", "Y5", "Z6 F300"});
  ASSERT_EQ(m.size(), 4u);
  EXPECT_EQ(m[0].kind, MotionKind::rapid);
  expect_near(m[0].start, {0, 0, 0});
  expect_near(m[0].end, {1, 2, 3});
  EXPECT_EQ(m[0].feed, 0.0);
  EXPECT_EQ(m[1].kind, MotionKind::linear);
  expect_near(m[1].start, {1, 2, 3});
  expect_near(m[1].end, {4, 2, 3});
  EXPECT_DOUBLE_EQ(m[1].feed, 200.0);
  expect_near(m[2].end, {4, 5, 3});
  EXPECT_EQ(m[2].kind, MotionKind::linear);
  EXPECT_DOUBLE_EQ(m[3].feed, 300.0);
  EXPECT_EQ(m[3].line, 4u);
}

TEST(Interpreter, MotionCodeWithoutAxisWordsMakesAZeroLengthMove) {
  // rs274ngc emits the move; so does abbe (same sequence of motions).
  const auto m = run_lines({"G0 X1", "G1 F100", "S1000 M3", "F50"});
  ASSERT_EQ(m.size(), 2u);
  expect_near(m[1].start, m[1].end);
}

TEST(Interpreter, IncrementalDistanceMode) {
  const auto m = run_lines({"G0 X1 Y1 Z1", "G91 G0 X1 Y-2", "Z0.5", "G90 X0"});
  expect_near(m[1].end, {2, -1, 1});
  expect_near(m[2].end, {2, -1, 1.5});
  expect_near(m[3].end, {0, -1, 1.5});
}

TEST(Interpreter, InchIsConvertedToMm) {
  const auto m = run_lines({"G20 G0 X1 Y2 Z-0.5", "G1 X2 F10", "G21 G0 X1"});
  expect_near(m[0].end, {25.4, 50.8, -12.7});
  expect_near(m[1].end, {50.8, 50.8, -12.7});
  EXPECT_NEAR(m[1].feed, 254.0, 1e-9);
  expect_near(m[2].end, {1, 50.8, -12.7});
}

TEST(Interpreter, WorkOffsetsG54ToG59) {
  InterpreterConfig config;
  config.work_offsets[0] = {10, 20, 30};
  config.work_offsets[1] = {100, 200, -50};
  config.work_offsets[5] = {-1, -2, -3};
  const auto m = run_lines({"G0 X1 Y2 Z3", "G55 G0 X1 Y2 Z3", "G59 X0", "G54 G0 X0 Y0 Z0"}, config);
  expect_near(m[0].end, {11, 22, 33});
  expect_near(m[1].end, {101, 202, -47});
  expect_near(m[2].end, {-1, 202, -47});  // switching G55 -> G59 does not move Y, Z
  expect_near(m[3].end, {10, 20, 30});
}

TEST(Interpreter, G92FamilyShiftsTheProgramFrame) {
  const auto m = run_lines({"G0 X10 Y5", "G92 X0", "G0 X5", "G92.2", "G0 X5", "G92.3", "G0 X5",
                            "G92.1", "G0 X5", "G92.3", "G0 X5"});
  expect_near(m[1].end, {15, 5, 0});  // G92 X0 at X10: offset 10
  expect_near(m[2].end, {5, 5, 0});   // G92.2: offset off, kept for G92.3
  expect_near(m[3].end, {15, 5, 0});  // G92.3 restores it
  expect_near(m[4].end, {5, 5, 0});   // G92.1 clears it
  expect_near(m[5].end, {5, 5, 0});   // and what G92.3 would restore
}

TEST(Interpreter, G92InInchProgram) {
  const auto m = run_lines({"G20 G0 X1", "G92 X0", "G0 X1"});
  expect_near(m[1].end, {50.8, 0, 0});
}

TEST(Interpreter, ToolLengthWithoutAndWithG43) {
  InterpreterConfig config;
  config.default_tool_length = 50;
  config.tool_lengths = {{1, 100.0}, {2, 120.0}};
  const auto m =
      run_lines({"G0 Z10", "G43 H1 G0 Z10", "G0 X1", "G49 G0 Z10", "T2 M6", "G43 G0 Z0"}, config);
  // Without G43 the program drives the spindle nose: P = s - L.
  expect_near(m[0].start, {0, 0, 0});  // initial position is the tool tip
  expect_near(m[0].end, {0, 0, -40});
  EXPECT_DOUBLE_EQ(m[0].tool_length, 50.0);
  // With G43 H1 the program point is the tool tip.
  expect_near(m[1].end, {0, 0, 10});
  EXPECT_DOUBLE_EQ(m[1].tool_length, 100.0);
  // A move without Z keeps the spindle where it is (as in rs274ngc).
  expect_near(m[2].end, {1, 0, 10});
  expect_near(m[3].end, {1, 0, -40});
  EXPECT_DOUBLE_EQ(m[3].tool_length, 50.0);
  // G43 without H uses the tool in the spindle (M6).
  expect_near(m[4].end, {1, 0, 0});
  EXPECT_DOUBLE_EQ(m[4].tool_length, 120.0);
  EXPECT_EQ(m[4].tool, 2);
}

TEST(Interpreter, G43ChangesTheProgramZOfTheCurrentPosition) {
  InterpreterConfig config;
  config.tool_lengths = {{1, 100.0}};
  const auto m = run_lines({"G0 Z10", "G43 H1", "G0 X1"}, config);
  // The spindle stays at s_z = 10; the tool tip is 100 mm below it.
  expect_near(m[1].end, {1, 0, -90});
  EXPECT_NE(error_of({"G43 H7"}, config).find("tool 7 has no length"), std::string::npos);
}

TEST(Interpreter, G53MovesInMachineCoordinates) {
  InterpreterConfig config;
  config.work_offsets[0] = {100, 200, -50};
  config.default_tool_length = 30;
  const auto m = run_lines({"G0 X1 Y1 Z1", "G53 G0 X0 Y0 Z0", "G0 X1"}, config);
  expect_near(m[1].end, {0, 0, -30});  // s = 0 -> tip 30 mm lower
  expect_near(m[2].end, {101, 0, -30});
  EXPECT_NE(error_of({"G91 G53 G0 X0"}).find("G53 in incremental"), std::string::npos);
  EXPECT_NE(error_of({"G53 G2 X1 I1 F1"}).find("G53 needs G0 or G1"), std::string::npos);
}

TEST(Interpreter, InitialPosition) {
  InterpreterConfig config;
  config.initial_position = {-100, -50, -10};
  const auto m = run_lines({"G91 G0 X1"}, config);
  expect_near(m[0].start, {-100, -50, -10});
  expect_near(m[0].end, {-99, -50, -10});
}

TEST(Interpreter, DwellAndCarriedWords) {
  const auto m = run_lines({"G0 X1 S1200 T4 M3", "G4 P1.5", "M8 M6", "G1 X2 F10 M9"});
  ASSERT_EQ(m.size(), 3u);
  EXPECT_EQ(m[1].kind, MotionKind::dwell);
  EXPECT_DOUBLE_EQ(m[1].dwell_seconds, 1.5);
  expect_near(m[1].start, {1, 0, 0});
  expect_near(m[1].end, {1, 0, 0});
  EXPECT_DOUBLE_EQ(m[0].spindle, 1200.0);
  EXPECT_EQ(m[0].tool, 4);
  EXPECT_EQ(m[2].tool, 4);
  EXPECT_NE(error_of({"G4"}).find("without a P word"), std::string::npos);
  EXPECT_NE(error_of({"G4 P-1"}).find("negative dwell"), std::string::npos);
}

TEST(Interpreter, ProgramEndStopsExecution) {
  Interpreter interp({}, "test.nc");
  std::vector<Motion> out;
  auto sink = [&](const Motion& m) { out.push_back(m); };
  interp.execute(make_block("G0 X1"), "G0 X1", sink);
  EXPECT_FALSE(interp.program_ended());
  interp.execute(make_block("M30"), "M30", sink);
  EXPECT_TRUE(interp.program_ended());
  interp.execute(make_block("G0 X5"), "G0 X5", sink);
  EXPECT_EQ(out.size(), 1u);
  expect_near(interp.position(), {1, 0, 0});
  Interpreter other({}, "t.nc");
  other.execute(make_block("M2"), "M2", sink);
  EXPECT_TRUE(other.program_ended());
}

TEST(Interpreter, BlockDeleteLinesAreExecuted) {
  // rs274ngc's block delete switch is off by default: '/' lines run.
  Interpreter interp({}, "test.nc");
  std::vector<Motion> out;
  Block block = make_block("G0 X5");
  block.block_delete = true;
  interp.execute(block, "/G0 X5", [&](const Motion& m) { out.push_back(m); });
  ASSERT_EQ(out.size(), 1u);
  expect_near(out[0].end, {5, 0, 0});
}

TEST(Interpreter, EmptyBlocksDoNothing) {
  Interpreter interp({}, "test.nc");
  int n = 0;
  Block block;
  block.line = 1;
  block.comments.push_back({0, 5, "hello"});
  interp.execute(block, "(hello)", [&](const Motion&) { ++n; });
  EXPECT_EQ(n, 0);
  expect_near(interp.position(), {0, 0, 0});
}

TEST(Interpreter, PathControlAndFeedModeAreAccepted) {
  const auto m = run_lines({"G61 G0 X1", "G64 P0.01 G0 X2", "G61.1 G94 G17 G40 G97 G0 X3"});
  ASSERT_EQ(m.size(), 3u);
  expect_near(m[2].end, {3, 0, 0});
}

TEST(Interpreter, ModalConflictsAreErrors) {
  EXPECT_NE(error_of({"G0 G1 X1"}).find("test.nc:1:4: error: two motion codes"), std::string::npos);
  EXPECT_NE(error_of({"G17 G18"}).find("two G codes of the same modal group"), std::string::npos);
  EXPECT_NE(error_of({"G90 G91"}).find("same modal group"), std::string::npos);
  EXPECT_NE(error_of({"G20 G21"}).find("same modal group"), std::string::npos);
  EXPECT_NE(error_of({"M3 M4"}).find("two M codes of the same modal group"), std::string::npos);
  EXPECT_NE(error_of({"M2 M30"}).find("two M codes"), std::string::npos);
  EXPECT_NE(error_of({"G0 X1 X2"}).find("test.nc:1:7: error: repeated X word"), std::string::npos);
  EXPECT_NE(error_of({"G0 G2 X1"}).find("two motion codes in one block (G0 and G2)"),
            std::string::npos);
  EXPECT_EQ(error_of({"G80 G0 X1"}), "");  // G80 may share a block; the other code wins
  EXPECT_EQ(run_lines({"G0 G80 X1"}).size(), 1u);
  EXPECT_NE(error_of({"G92 G0 X1"}).find("both use axis words"), std::string::npos);
  EXPECT_NE(error_of({"G80 X1"}).find("axis words with G80"), std::string::npos);
  EXPECT_NE(error_of({"X1"}).find("axis words without a motion code"), std::string::npos);
  EXPECT_NE(error_of({"G1 X1"}).find("G1 with zero feed rate"), std::string::npos);
}

TEST(Interpreter, UnusedWordsAreErrors) {
  EXPECT_NE(error_of({"G0 X1 R2"}).find("R word with no"), std::string::npos);
  EXPECT_NE(error_of({"G0 X1 I2"}).find("I word with no G2, G3 or G87"), std::string::npos);
  EXPECT_NE(error_of({"G0 X1 P2"}).find("P word with no"), std::string::npos);
  EXPECT_NE(error_of({"G0 X1 Q2"}).find("Q word with no"), std::string::npos);
  EXPECT_NE(error_of({"G0 X1 L2"}).find("L word with no"), std::string::npos);
  EXPECT_NE(error_of({"G0 H2"}).find("H word with no G43"), std::string::npos);
}

TEST(Interpreter, UnsupportedConstructsAreRefusedByName) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"G41 D1",
       "cutter radius compensation (G41/G42) is not supported by a command that "
       "rewrites the program line by line"},
      {"G42.1 D2", "cutter radius compensation (G41/G42) is not supported by a command"},
      {"G0 @1 ^2", "polar coordinates (@, ^) are not supported by a command"},
      {"G43.1 Z2", "(G43.1) is not supported by a command that rewrites"},
      {"G68 X0 Y0 R45", "coordinate system rotation (G68) is not supported"},
      {"G33 Z-1 K1", "spindle-synchronised motion (threading) (G33)"},
      {"G76 P1 Z-1", "(G76) is not supported"},
      {"G38.2 Z-1 F10", "probing (G38.2) is not supported"},
      {"G5 X1 Y1 I1 J0 P1 Q0", "spline / NURBS motion (G5) is not supported"},
      {"G5.1 X1 Y1 I1 J0", "(G5.1) is not supported"},
      {"G7", "lathe diameter/radius mode (G7)"},
      {"G16", "polar coordinate mode (G16) is not supported"},
      {"G0 A10", "rotary axis A moves (from A0 to A10)"},
      {"G88 X0 Z-1 R1 P1", "boring cycle with a manual retract (G88) is not supported"},
      {"G10 L11 P1 Z0", "tool data relative to a fixture (G10 L11) is not supported"},
      {"G10 L2 P8 X0", "coordinate system beyond G59 (G10 L2 P8)"},
      {"G10 L1 P1 X1 Z2", "X offset of a tool (G10 L1 X) is not supported"},
      {"G0 W1", "W axis words are not supported"},
      {"G12.3", "unknown G code G12.3"},
      {"G0.5 X1", "unknown G code G0.5"},
      {"M123", "M code M123 is not supported"},
      {"G59.1", "coordinate system beyond G59 (G59.1) is not supported"},
  };
  for (const auto& [line, message] : cases) {
    const std::string e = error_of({line});
    EXPECT_NE(e.find(message), std::string::npos) << line << " -> " << e;
    EXPECT_EQ(e.rfind("test.nc:1:", 0), 0u) << e;
  }
}

TEST(Interpreter, HomeThroughTheIntermediatePoint) {
  InterpreterConfig config;
  config.g28_position = {10, 20, 30};
  config.g30_position = {-1, -2, -3};
  const auto m =
      run_lines({"G0 X1 Y2 Z3", "G28 G91 Z1", "G90 G28.1", "G0 X5", "G28", "G30 Y7"}, config);
  ASSERT_EQ(m.size(), 8u);
  expect_near(m[1].end, {1, 2, 4});    // intermediate point: Z one up (G91)
  expect_near(m[2].end, {1, 2, 30});   // only Z goes home
  expect_near(m[4].end, {5, 2, 30});   // G28 without axis words: through where it is
  expect_near(m[5].end, {1, 2, 30});   // to the position G28.1 stored
  expect_near(m[6].end, {1, 7, 30});   // G30 Y7: intermediate Y7
  expect_near(m[7].end, {1, -2, 30});  // Y to the stored G30 position
}

TEST(Interpreter, HomeIsInMachineCoordinatesWhateverTheOffsets) {
  InterpreterConfig config;
  config.g28_position = {0, 0, 0};
  config.work_offsets[1] = {100, 0, 0};
  config.tool_lengths[1] = 50;
  const auto m = run_lines({"G55 G43 H1 G0 X1 Y1 Z1", "G28 Z5", "G20 G0 X1"}, config);
  ASSERT_EQ(m.size(), 4u);
  // The spindle nose goes to machine Z0; the tool tip hangs 50 mm below it.
  expect_near(m[2].end, {101, 1, -50});
  expect_near(m[3].end, {125.4, 1, -50});
}

TEST(Interpreter, G10SetsWorkOffsetsAndToolLengths) {
  const auto m =
      run_lines({"G0 X10 Y10 Z10", "G10 L20 P1 X2", "G0 X2", "G10 L2 P2 X-5", "G55 G0 X0",
                 "G10 L1 P3 Z40", "G43 H3 G0 Z0", "G10 L10 P4 Z1", "G43 H4 G0 Z1"});
  ASSERT_EQ(m.size(), 5u);
  expect_near(m[1].end, {10, 10, 10});  // L20: the current point reads X2
  expect_near(m[2].end, {-5, 10, 10});  // L2: G55's origin at X-5
  expect_near(m[3].end, {-5, 10, 0});   // G43 with the length G10 L1 set: the tip at Z0
  EXPECT_DOUBLE_EQ(m[3].tool_length, 40.0);
  // L10: the length that makes the current Z read 1 with tool 4.
  expect_near(m[4].end, {-5, 10, 1});
  EXPECT_DOUBLE_EQ(m[4].tool_length, 39.0);
}

TEST(Interpreter, G52MovesTheFrameLikeG92) {
  const auto m = run_lines({"G0 X1", "G52 X10", "G0 X1", "G92.1", "G0 X1"});
  ASSERT_EQ(m.size(), 3u);
  expect_near(m[1].end, {11, 0, 0});
  expect_near(m[2].end, {1, 0, 0});
}

TEST(Interpreter, FeedModesGiveTheFeedRateOfEachMove) {
  const auto m = run_lines({"G1 X10 F100", "G93 G1 X40 F2", "G3 X40 Y0 I-10 J0 F0.5",
                            "G95 S500 G1 X0 F0.2", "G94 G1 X1 F300"});
  ASSERT_EQ(m.size(), 5u);
  EXPECT_DOUBLE_EQ(m[0].feed, 100.0);
  EXPECT_DOUBLE_EQ(m[1].feed, 60.0);                                  // 30 mm in 1/2 min
  EXPECT_NEAR(m[2].feed, 2.0 * 3.14159265358979 * 10.0 * 0.5, 1e-9);  // full circle in 2 min
  EXPECT_DOUBLE_EQ(m[3].feed, 100.0);                                 // 0.2 mm/rev at 500 rpm
  EXPECT_DOUBLE_EQ(m[4].feed, 300.0);
  EXPECT_NE(error_of({"G93 G1 X1 F1", "X2"}).find("F word missing in inverse-time"),
            std::string::npos);
  EXPECT_NE(error_of({"G95 G1 X1 F1"}).find("spindle speed 0"), std::string::npos);
}

TEST(Interpreter, PathControlIsCarried) {
  const std::vector<std::string> lines{"G61", "G64 P0.01 Q0.02"};
  InterpreterConfig config;
  Interpreter interp(config, "t.nc");
  const MotionSink none = [](const Motion&) {};
  interp.execute(make_block(lines[0]), lines[0], none);
  EXPECT_EQ(interp.modal().path_control, PathControl::exact_path);
  interp.execute(make_block(lines[1]), lines[1], none);
  EXPECT_EQ(interp.modal().path_control, PathControl::blending);
  EXPECT_DOUBLE_EQ(interp.modal().blend_tolerance, 0.01);
  EXPECT_DOUBLE_EQ(interp.modal().naive_cam_tolerance, 0.02);
}

TEST(Interpreter, TappingAndBoringCycles) {
  const auto m = run_lines({"F100 S500 M3", "G0 Z5", "G99 G84 X1 Z-2 R1", "G80", "M4",
                            "G74 X2 Z-2 R1 P0.5", "G80", "G86 X3 Z-2 R1 P1"});
  // G84: over the hole, down to R, feed in, dwell 0, feed out to R.
  ASSERT_GE(m.size(), 6u);
  expect_near(m[3].end, {1, 0, -2});
  EXPECT_EQ(m[4].kind, MotionKind::dwell);
  EXPECT_EQ(m[5].kind, MotionKind::linear);
  expect_near(m[5].end, {1, 0, 1});
  const Motion& last = m.back();
  EXPECT_EQ(last.kind, MotionKind::rapid);  // G86 rapids out
  expect_near(last.end, {3, 0, 1});
  EXPECT_NE(error_of({"F100", "G0 Z5", "G84 X1 Z-2 R1"}).find("not turning clockwise"),
            std::string::npos);
}

TEST(Interpreter, UnknownToolLengthWhereAllowed) {
  InterpreterConfig config;
  EXPECT_NE(error_of({"G43 H7"}, config).find("tool 7 has no length"), std::string::npos);
  config.allow_unknown_tool_length = true;
  config.default_tool_length = 20;
  const auto m = run_lines({"G0 Z10", "G43 H7 G0 Z10", "G49 G0 Z10"}, config);
  ASSERT_EQ(m.size(), 3u);
  expect_near(m[1].end, {0, 0, 10});  // the tip path does not depend on L under G43
  EXPECT_TRUE(std::isnan(m[1].tool_length));
  EXPECT_DOUBLE_EQ(m[2].tool_length, 20.0);
}

TEST(Interpreter, RotaryWordsThatDoNotMove) {
  const auto m = run_lines({"G0 X1 A0 B0", "G91 G0 X1 C0", "G90 A0"});
  ASSERT_EQ(m.size(), 3u);
  expect_near(m[1].end, {2, 0, 0});
  expect_near(m[2].end, {2, 0, 0});  // a rotary word alone: a zero-length move
  EXPECT_NE(error_of({"G91 G0 B5"}).find("rotary axis B moves"), std::string::npos);
}

TEST(Interpreter, MotionToString) {
  EXPECT_STREQ(to_string(MotionKind::rapid), "rapid");
  EXPECT_STREQ(to_string(MotionKind::linear), "linear");
  EXPECT_STREQ(to_string(MotionKind::arc), "arc");
  EXPECT_STREQ(to_string(MotionKind::dwell), "dwell");
}

}  // namespace
}  // namespace abbe::gcode
