// The Fanuc/Haas dialect: numbers without a decimal point, dwell units,
// cycle repeats K, carried look-ahead codes, M98/M99 subprograms between the
// O-numbered programs of one file, and what is refused by name. Expected
// points are worked out by hand from the Fanuc conventions (docs/fanuc.md).
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "abbe/gcode/program.hpp"
#include "abbe/io/input_error.hpp"

namespace abbe::gcode {
namespace {

std::vector<Motion> run(const std::string& text,
                        IntegerNumbers integers = IntegerNumbers::least_increment,
                        Dialect dialect = Dialect::fanuc) {
  InterpreterConfig config;
  config.dialect.dialect = dialect;
  config.dialect.integers = integers;
  std::istringstream in(text);
  std::vector<Motion> out;
  run_program(in, "f.nc", config, [&](const Motion& m) { out.push_back(m); });
  return out;
}

std::string error_of(const std::string& text) {
  try {
    run(text);
  } catch (const InputError& e) {
    const std::string what = e.what();
    return what.substr(0, what.find('\n'));  // without the caret display
  }
  return "no error";
}

void expect_end(const Motion& m, double x, double y, double z) {
  EXPECT_NEAR(m.end.x(), x, 1e-12);
  EXPECT_NEAR(m.end.y(), y, 1e-12);
  EXPECT_NEAR(m.end.z(), z, 1e-12);
}

TEST(FanucDialect, LengthsWithoutPointAreLeastIncrements) {
  const auto m = run("G21 G90\nG0 X100 Y-2500 Z5.\nG1 X10. Y.5 F1000\nM30\n");
  ASSERT_EQ(m.size(), 2U);
  expect_end(m[0], 0.1, -2.5, 5.0);
  expect_end(m[1], 10.0, 0.5, 5.0);
  EXPECT_DOUBLE_EQ(m[1].feed, 1000.0);  // F is not scaled
}

TEST(FanucDialect, InchIncrementIsATenThousandth) {
  const auto m = run("G20 G90\nG0 X1000 Z-25\n");
  ASSERT_EQ(m.size(), 1U);
  expect_end(m[0], 0.1 * 25.4, 0.0, -0.0025 * 25.4);
}

TEST(FanucDialect, CalculatorTypeInputReadsWholeUnits) {
  const auto m = run("G21 G90\nG0 X100 Y-25 Z5.\n", IntegerNumbers::whole_units);
  ASSERT_EQ(m.size(), 1U);
  expect_end(m[0], 100.0, -25.0, 5.0);
}

TEST(FanucDialect, ProgramWithPointsEverywhereMeansTheSameInBothDialects) {
  const std::string text =
      "G17 G21 G90\nG0 X10. Y5. Z2.\nG1 Z-1. F200.\nG2 X20. Y5. I5. J0.\nG3 X10. Y5. R5.\n"
      "G91 G1 X-2.5 Y1.\nG90 G0 Z10.\n";
  const auto fanuc = run(text);
  const auto linuxcnc = run(text, IntegerNumbers::least_increment, Dialect::linuxcnc);
  ASSERT_EQ(fanuc.size(), linuxcnc.size());
  for (std::size_t i = 0; i < fanuc.size(); ++i) {
    EXPECT_EQ(fanuc[i].kind, linuxcnc[i].kind);
    EXPECT_EQ((fanuc[i].end - linuxcnc[i].end).norm(), 0.0) << "motion " << i;
  }
}

TEST(FanucDialect, DwellInMillisecondsOrSeconds) {
  const auto m = run("G04 P1500\nG04 X2.\nG04 X250\nG04 P1.5\n");
  ASSERT_EQ(m.size(), 4U);
  EXPECT_DOUBLE_EQ(m[0].dwell_seconds, 1.5);  // P without a point: ms
  EXPECT_DOUBLE_EQ(m[1].dwell_seconds, 2.0);  // X: seconds
  EXPECT_DOUBLE_EQ(m[2].dwell_seconds, 0.25);
  EXPECT_DOUBLE_EQ(m[3].dwell_seconds, 1.5);  // P with a point: seconds (Haas)
}

TEST(FanucDialect, CycleRepeatsKAreLinuxcncL) {
  const std::string head = "G17 G21 G90 G0 X0. Y0. Z10.\nG91 G98 G81 X10. Y0. Z-5. R-8. ";
  const auto fanuc = run(head + "K3 F100.\nG80\n");
  const auto linuxcnc =
      run(head + "L3 F100.\nG80\n", IntegerNumbers::least_increment, Dialect::linuxcnc);
  ASSERT_EQ(fanuc.size(), linuxcnc.size());
  ASSERT_GT(fanuc.size(), 6U);
  for (std::size_t i = 0; i < fanuc.size(); ++i)
    EXPECT_EQ((fanuc[i].end - linuxcnc[i].end).norm(), 0.0) << "motion " << i;
  expect_end(fanuc.back(), 30.0, 0.0, 10.0);  // three holes 10 mm apart, back at the initial level
}

TEST(FanucDialect, LookAheadAndSmoothingCodesAreCarried) {
  const auto m = run("G05.1 Q1\nG08 P1\nG187 P1\nG103 P1\nG05 P10000\nG69\nG15\nG50\nG0 X1.\n");
  ASSERT_EQ(m.size(), 1U);
  expect_end(m[0], 1.0, 0.0, 0.0);
}

const char* kSubprogramFile =
    "%\n"
    "O1000 (MAIN)\n"
    "G90 G21\n"
    "G0 X0. Y0. Z10.\n"
    "M98 P2000 L3\n"
    "G0 X100.\n"
    "M30\n"
    "O2000 (SUB: ONE MM STEP)\n"
    "G91 G1 X1. F100.\n"
    "G90\n"
    "M99\n"
    "%\n";

TEST(FanucDialect, SubprogramCalledThreeTimes) {
  const auto m = run(kSubprogramFile);
  ASSERT_EQ(m.size(), 5U);
  expect_end(m[0], 0.0, 0.0, 10.0);
  for (int pass = 0; pass < 3; ++pass) {
    expect_end(m[static_cast<std::size_t>(1 + pass)], 1.0 + pass, 0.0, 10.0);
    EXPECT_EQ(m[static_cast<std::size_t>(1 + pass)].line, 9U);  // the subprogram's line
  }
  expect_end(m[4], 100.0, 0.0, 10.0);
  EXPECT_EQ(m[4].line, 6U);
}

TEST(FanucDialect, EightDigitPCarriesTheRepeatCount) {
  std::string text = kSubprogramFile;
  text.replace(text.find("M98 P2000 L3"), 12, "M98 P32000");  // 3 x O2000
  const auto m = run(text);
  ASSERT_EQ(m.size(), 5U);
  expect_end(m[3], 3.0, 0.0, 10.0);
}

TEST(FanucDialect, NestedSubprograms) {
  const auto m =
      run("O1\nG90 G0 X0. Y0. Z0.\nM98 P2 L2\nM30\n"
          "O2\nM98 P3 L2\nG91 G0 Y1.\nG90\nM99\n"
          "O3\nG91 G0 X1.\nG90\nM99\n");
  // O2 twice; each pass: O3 twice (X+1, X+1) then Y+1.
  ASSERT_EQ(m.size(), 7U);
  expect_end(m.back(), 4.0, 2.0, 0.0);
}

TEST(FanucDialect, M99InTheMainProgramEndsIt) {
  const auto m = run("O1\nG0 X1.\nM99\nG0 X5.\n");
  ASSERT_EQ(m.size(), 1U);
}

TEST(FanucDialect, MainProgramEndsWhereTheNextProgramBegins) {
  const auto m = run("O1\nG0 X1.\nO2\nG0 X5.\nM99\n");
  ASSERT_EQ(m.size(), 1U);
}

TEST(FanucDialect, SecondPercentEndsTheFile) {
  const auto m = run("%\nO1\nG0 X1.\n%\nG0 X5.\n");
  ASSERT_EQ(m.size(), 1U);
}

TEST(FanucDialect, RefusalsNameTheConstruct) {
  EXPECT_EQ(error_of("G0 X1.\nG68 X0. Y0. R45.\n"),
            "f.nc:2:1: error: coordinate rotation (G68) is not supported");
  EXPECT_EQ(error_of("G51 X0 Y0 P2000\n"), "f.nc:1:1: error: scaling (G51) is not supported");
  EXPECT_EQ(error_of("G54.1 P1\n"),
            "f.nc:1:1: error: additional work offsets (G54.1) is not "
            "supported");
  EXPECT_EQ(error_of("O1\nM98 P9999\nM30\n"),
            "f.nc:2:1: error: subprogram O9999 is not in this file");
  EXPECT_EQ(error_of("M98\n"), "f.nc:1:1: error: M98 without P (the program number to call)");
  EXPECT_EQ(error_of("M97 P100\n"),
            "f.nc:1:1: error: local subprogram call (M97) is not supported; use M98 with an "
            "O-numbered program");
  EXPECT_EQ(error_of("O1\nM98 P2\nM30\nO2\nG0 X1.\n"),
            "f.nc:5: error: the file ends inside a subprogram (no M99)");
  EXPECT_EQ(error_of("O1\nM98 P1\n"), "f.nc:2:1: error: subprograms nested deeper than 10 levels");
  EXPECT_EQ(error_of("O1\nM30\nO1\nM99\n"),
            "f.nc:3:1: error: program number O1 is defined twice in this file");
}

}  // namespace
}  // namespace abbe::gcode
