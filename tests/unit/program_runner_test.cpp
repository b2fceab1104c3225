// Parameters, expressions and O-word control flow (src/gcode/program_runner.cpp):
// end points of small programs, each value worked out by hand from rs274ngc's
// rules (precedence, degrees, "settings take effect after the line").
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "abbe/gcode/parser.hpp"
#include "abbe/gcode/program.hpp"
#include "abbe/io/input_error.hpp"

namespace {

using abbe::gcode::InterpreterConfig;
using abbe::gcode::Motion;

std::vector<Eigen::Vector3d> ends(const std::string& program, InterpreterConfig config = {}) {
  std::istringstream in(program);
  std::vector<Eigen::Vector3d> out;
  abbe::gcode::run_program(in, "t.ngc", config, [&](const Motion& m) { out.push_back(m.end); });
  return out;
}

double x_of(const std::string& expression) {
  const auto e = ends("G21\nG0 X" + expression + "\n");
  EXPECT_EQ(e.size(), 1u) << expression;
  return e.empty() ? 0.0 : e[0].x();
}

std::string error_of(const std::string& program) {
  try {
    ends(program);
  } catch (const abbe::InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Expressions, PrecedenceAndAssociativity) {
  EXPECT_DOUBLE_EQ(x_of("[1+2*3]"), 7.0);
  EXPECT_DOUBLE_EQ(x_of("[2**3**2]"), 64.0);  // left-associative, as rs274ngc
  EXPECT_DOUBLE_EQ(x_of("[2*3**2]"), 18.0);
  EXPECT_DOUBLE_EQ(x_of("[10-4-3]"), 3.0);
  EXPECT_DOUBLE_EQ(x_of("[1+1 EQ 2]"), 1.0);
  EXPECT_DOUBLE_EQ(x_of("[1 LT 2 AND 3 GT 4]"), 0.0);
  EXPECT_DOUBLE_EQ(x_of("[1 OR 0 XOR 1]"), 0.0);  // (1 OR 0) XOR 1
  EXPECT_DOUBLE_EQ(x_of("[-7 MOD 3]"), 2.0);      // non-negative, as rs274ngc
  EXPECT_DOUBLE_EQ(x_of("[7 mod 3]"), 1.0);
  EXPECT_DOUBLE_EQ(x_of("-[2]"), -2.0);
  EXPECT_DOUBLE_EQ(x_of("[1 - -2]"), 3.0);
  // rs274ngc reads a sign before any value: X--1 is 1, X+-1 is -1.
  EXPECT_DOUBLE_EQ(x_of("--1"), 1.0);
  EXPECT_DOUBLE_EQ(x_of("+-1"), -1.0);
}

TEST(Expressions, Functions) {
  EXPECT_NEAR(x_of("SIN[30]"), 0.5, 1e-12);
  EXPECT_NEAR(x_of("[COS[60]]"), 0.5, 1e-12);
  EXPECT_NEAR(x_of("ATAN[1]/[1]"), 45.0, 1e-12);
  EXPECT_NEAR(x_of("[ACOS[0]]"), 90.0, 1e-12);
  EXPECT_DOUBLE_EQ(x_of("[SQRT[16]]"), 4.0);
  EXPECT_DOUBLE_EQ(x_of("[ABS[-3]]"), 3.0);
  EXPECT_DOUBLE_EQ(x_of("[FIX[-2.5]]"), -3.0);
  EXPECT_DOUBLE_EQ(x_of("[FUP[2.1]]"), 3.0);
  EXPECT_DOUBLE_EQ(x_of("[ROUND[2.5]]"), 3.0);
  EXPECT_DOUBLE_EQ(x_of("[ROUND[-2.5]]"), -3.0);
  EXPECT_NEAR(x_of("[LN[EXP[2]]]"), 2.0, 1e-12);
  EXPECT_DOUBLE_EQ(x_of("[EXISTS[#<nope>]]"), 0.0);
}

TEST(Parameters, SettingsTakeEffectAfterTheLine) {
  const auto e = ends("G21\n#1=5\n#1=10 G0 X#1\nG0 X#1\n");
  ASSERT_EQ(e.size(), 2u);
  EXPECT_DOUBLE_EQ(e[0].x(), 5.0);
  EXPECT_DOUBLE_EQ(e[1].x(), 10.0);
  // Two settings on a line both read the old values.
  const auto f = ends("G21\n#1=1 #2=2\n#1=#2 #2=#1\nG0 X#1 Y#2\n");
  ASSERT_EQ(f.size(), 1u);
  EXPECT_DOUBLE_EQ(f[0].x(), 2.0);
  EXPECT_DOUBLE_EQ(f[0].y(), 1.0);
}

TEST(Parameters, NamedIndirectAndPredefined) {
  const auto e = ends("G21\n#<a> = 3\n#<_G> = 4\n#[#<a>+1] = 7\nG0 X#4 Y#<_g> Z##<a>\n");
  ASSERT_EQ(e.size(), 1u);
  EXPECT_DOUBLE_EQ(e[0].x(), 7.0);
  EXPECT_DOUBLE_EQ(e[0].y(), 4.0);
  EXPECT_DOUBLE_EQ(e[0].z(), 0.0);  // #3 was never set
  // #5420..#5422: the current position.
  const auto p = ends("G21\nG0 X2 Y3\nG0 X[#5420+#5421]\n");
  ASSERT_EQ(p.size(), 2u);
  EXPECT_DOUBLE_EQ(p[1].x(), 5.0);
  EXPECT_DOUBLE_EQ(p[1].y(), 3.0);
}

// Three predefined named parameters read after `setup`, returned through a
// G53 move (machine coordinates, no tool length, mm).
Eigen::Vector3d predefined(const std::string& setup, const std::string& a, const std::string& b,
                           const std::string& c) {
  InterpreterConfig config;
  config.tool_lengths[1] = 12.7;
  config.tool_diameters[1] = 2.54;
  const auto e = ends(setup + "#1=#<" + a + "> #2=#<" + b + "> #3=#<" + c +
                          ">\nG40\nG49 G80 G21 G90\nG53 G0 X#1 Y#2 Z#3\n",
                      config);
  return e.empty() ? Eigen::Vector3d::Constant(-1e9) : e.back();
}

TEST(Parameters, PredefinedNamedMirrorTheState) {
  // Values as the standalone rs274 (LinuxCNC 2.9) printed them for the same
  // program with tool 1 of length 0.5 in (12.7 mm).
  const std::string s1 = "G21 G90 G17\nG10 L2 P1 X100 Y0 Z0\nT1 M6\nG43 H1\nG0 X1 Y2 Z3\n";
  Eigen::Vector3d v = predefined(s1, "_x", "_abs_x", "_abs_z");
  EXPECT_NEAR(v.x(), 1.0, 1e-12);
  EXPECT_NEAR(v.y(), 101.0, 1e-12);
  EXPECT_NEAR(v.z(), 15.7, 1e-12);  // Z 3 + tool length 12.7
  EXPECT_EQ(predefined(s1, "_ccomp", "_current_tool", "_tool_offset"), Eigen::Vector3d(400, 1, 1));
  EXPECT_EQ(predefined(s1, "_motion_mode", "_plane", "_coord_system"),
            Eigen::Vector3d(0, 170, 540));
  EXPECT_EQ(predefined(s1, "_metric", "_imperial", "_absolute"), Eigen::Vector3d(1, 0, 1));
  const std::string s2 = s1 + "M3 S1000 M8\nG41 G1 X20 F200\n";
  EXPECT_EQ(predefined(s2, "_ccomp", "_rpm", "_flood"), Eigen::Vector3d(410, 1000, 1));
  EXPECT_EQ(predefined(s2, "_spindle_on", "_spindle_cw", "_motion_mode"),
            Eigen::Vector3d(1, 1, 10));
  const std::string s3 = s2 + "G40 G1 X30\nG81 X40 Y2 R5 Z-1\n";
  EXPECT_EQ(predefined(s3, "_motion_mode", "_retract_r_plane", "_retract_old_z"),
            Eigen::Vector3d(810, 1, 0));
  v = predefined(s3 + "G80\nG20\n", "_x", "_feed", "_imperial");
  EXPECT_NEAR(v.x(), 40.0 / 25.4, 1e-12);
  EXPECT_EQ(v.y(), 200.0);  // the F word as written, not converted
  EXPECT_EQ(v.z(), 1.0);
  EXPECT_EQ(predefined("G0 X1\nM9\nG42.1 D1 G1 X3 F1\n", "_ccomp", "_mist", "_task"),
            Eigen::Vector3d(421, 0, 0));
  // The line being executed and the subroutine call level.
  const auto line = ends("G21\n\nG0 X#<_line> Y[EXISTS[#<_y>]]\n");
  ASSERT_EQ(line.size(), 1u);
  EXPECT_EQ(line[0], Eigen::Vector3d(3, 1, 0));
  const auto level =
      ends("G21\no1 sub\nG0 Y#<_call_level>\no1 endsub\no1 call\nG0 X#<_call_level>\n");
  ASSERT_EQ(level.size(), 2u);
  EXPECT_EQ(level[0].y(), 1.0);
  EXPECT_EQ(level[1].x(), 0.0);
  // Read-only, as in rs274ngc; names abbe does not follow stay undefined.
  EXPECT_NE(error_of("G21\n#<_x> = 5\n")
                .find("t.ngc:2:1: error: cannot assign to the read-only parameter #<_x>"),
            std::string::npos);
  EXPECT_NE(error_of("G0 X#<_current_pocket>\n").find("#<_current_pocket> is not defined"),
            std::string::npos);
}

TEST(ControlFlow, SubroutineWithArgumentsAndLocalScope) {
  const auto e = ends(
      "G21\n#1=100\no<move> sub\n#<x> = [#1*2]\nG0 X#<x> Y#2\no<move> endsub\n"
      "o<move> call [1] [5]\no<move> call [3]\nG0 Z#1\nM2\n");
  ASSERT_EQ(e.size(), 3u);
  EXPECT_DOUBLE_EQ(e[0].x(), 2.0);
  EXPECT_DOUBLE_EQ(e[0].y(), 5.0);
  EXPECT_DOUBLE_EQ(e[1].x(), 6.0);
  EXPECT_DOUBLE_EQ(e[1].y(), 0.0);    // #2 not passed: 0
  EXPECT_DOUBLE_EQ(e[2].z(), 100.0);  // #1 restored after the calls
}

TEST(ControlFlow, CallBeforeDefinitionAndReturnValue) {
  const auto e =
      ends("G21\no100 call [4]\nG0 X#<_value>\nM2\no100 sub\no100 return [#1*#1]\no100 endsub\n");
  ASSERT_EQ(e.size(), 1u);
  EXPECT_DOUBLE_EQ(e[0].x(), 16.0);
}

TEST(Parameters, VarFileAndSubroutineFolder) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "abbe_program_runner_test";
  fs::create_directories(dir);
  {
    std::ofstream var(dir / "params.var");
    var << "1\t42.5\n5161 3\nnot a parameter line\n";
    std::ofstream sub(dir / "square.ngc");
    sub << "(a subroutine file)\no<square> sub\nG1 X[#1*#1] F100\no<square> endsub\n";
  }
  InterpreterConfig config;
  config.dialect.var_file = (dir / "params.var").string();
  config.dialect.subroutine_path = dir.string();
  const auto e = ends("G21\nG0 X#1 Y#5161\no<square> call [3]\nG0 Y#1\n", config);
  ASSERT_EQ(e.size(), 3u);
  EXPECT_DOUBLE_EQ(e[0].x(), 42.5);
  EXPECT_DOUBLE_EQ(e[0].y(), 3.0);
  EXPECT_DOUBLE_EQ(e[1].x(), 9.0);   // from square.ngc
  EXPECT_DOUBLE_EQ(e[2].y(), 42.5);  // #1 restored after the call
  // #5220 (G55 = 2) and #5400 (tool in the spindle after M6).
  const auto p = ends("G21\nG55\nT3 M6\nG0 X#5220 Y#5400\n");
  ASSERT_FALSE(p.empty());
  EXPECT_DOUBLE_EQ(p.back().x(), 2.0);
  EXPECT_DOUBLE_EQ(p.back().y(), 3.0);
  fs::remove_all(dir);
}

TEST(ControlFlow, IfElseifElse) {
  const std::string p =
      "G21\n#1=VALUE\no1 if [#1 LT 0]\nG0 X-1\no1 elseif [#1 EQ 0]\nG0 X0.5\no1 else\nG0 X1\n"
      "o1 endif\nG0 Y9\n";
  for (const auto& [value, x] :
       std::vector<std::pair<std::string, double>>{{"-3", -1.0}, {"0", 0.5}, {"2", 1.0}}) {
    std::string q = p;
    q.replace(q.find("VALUE"), 5, value);
    const auto e = ends(q);
    ASSERT_EQ(e.size(), 2u) << value;
    EXPECT_DOUBLE_EQ(e[0].x(), x) << value;
    EXPECT_DOUBLE_EQ(e[1].y(), 9.0);
  }
}

TEST(ControlFlow, Loops) {
  // while with break and continue: X 1, 3 (2 skipped), stop at 4.
  const auto w = ends(
      "G21\n#1=0\no1 while [#1 LT 10]\n#1=[#1+1]\no2 if [#1 EQ 2]\no1 continue\no2 endif\n"
      "o3 if [#1 EQ 4]\no1 break\no3 endif\nG0 X#1\no1 endwhile\nG0 Y1\n");
  ASSERT_EQ(w.size(), 3u);
  EXPECT_DOUBLE_EQ(w[0].x(), 1.0);
  EXPECT_DOUBLE_EQ(w[1].x(), 3.0);
  EXPECT_DOUBLE_EQ(w[2].y(), 1.0);
  // do/while runs at least once; repeat n times.
  EXPECT_EQ(ends("G21\no1 do\nG0 X1\no1 while [0]\n").size(), 1u);
  EXPECT_EQ(ends("G21\n#1=0\no1 do\n#1=[#1+1]\nG0 X#1\no1 while [#1 LT 3]\n").size(), 3u);
  EXPECT_EQ(ends("G21\no7 repeat [4]\nG0 X1\no7 endrepeat\n").size(), 4u);
  EXPECT_EQ(ends("G21\no7 repeat [0]\nG0 X1\no7 endrepeat\n").size(), 0u);
}

TEST(ControlFlow, LoopLimitIsAClearError) {
  InterpreterConfig config;
  config.dialect.loop_limit = 100;
  std::string what;
  try {
    ends("G21\no1 while [1]\nG0 X1\no1 endwhile\n", config);
  } catch (const abbe::InputError& e) {
    what = e.what();
  }
  EXPECT_NE(what.find("t.ngc:4:1: error: more than 100 loop iterations (o1 endwhile)"),
            std::string::npos)
      << what;
}

TEST(Errors, NameFileLineAndColumn) {
  EXPECT_NE(error_of("G0 X[1/0]\n").find("t.ngc:1:7: error: division by zero"), std::string::npos);
  EXPECT_NE(
      error_of("G0 X#<nope>\n").find("t.ngc:1:5: error: named parameter #<nope> is not defined"),
      std::string::npos);
  EXPECT_NE(error_of("#0 = 1\n").find("t.ngc:1:1: error: parameter number #0 is out of range"),
            std::string::npos);
  EXPECT_NE(
      error_of("o9 endwhile\n").find("t.ngc:1:1: error: o9 endwhile without its opening line"),
      std::string::npos);
  EXPECT_NE(error_of("G0 X[ACOS[2]]\n").find("t.ngc:1:6: error: ACOS of 2"), std::string::npos);
}

TEST(Errors, LineByLineCallersAndTheFanucDialectRefuseThemByName) {
  // Interpreter::execute (compensate, verify) cannot evaluate: it refuses.
  abbe::gcode::Interpreter interpreter(InterpreterConfig{}, "t.ngc");
  const auto block = abbe::gcode::parse_line("G0 X1 Y#1", 3, "t.ngc");
  std::string what;
  try {
    interpreter.execute(block, "G0 X1 Y#1", [](const Motion&) {});
  } catch (const abbe::InputError& e) {
    what = e.what();
  }
  EXPECT_NE(what.find("t.ngc:3:7: error: parameters, expressions and O-words are not supported by "
                      "a command that rewrites the program line by line"),
            std::string::npos)
      << what;
  InterpreterConfig fanuc;
  fanuc.dialect.dialect = abbe::gcode::Dialect::fanuc;
  what.clear();
  try {
    ends("G21\n#1=2\n", fanuc);
  } catch (const abbe::InputError& e) {
    what = e.what();
  }
  EXPECT_NE(what.find("t.ngc:2:1: error: macro variables, expressions and O-word control flow"),
            std::string::npos)
      << what;
}

}  // namespace

namespace {

// run_program's count of motions is the number of sink calls, with the
// motions cutter compensation still holds at the end, those of a
// subroutine called in a loop, and a canned cycle's several motions.
TEST(ProgramStats, MotionsAreTheSinkCalls) {
  const std::vector<std::string> programs = {
      "G21 G0 X0 Y-10 F100\nG41.1 D4 G1 X0 Y0\nG3 X10 Y0 I5 J0\nG1 Y-10\n",
      "o<p> sub\nG1 X#1 F100\no<p> endsub\n#2=0\no1 while [#2 LT 5]\no<p> call [#2]\n#2=[#2+1]\n"
      "o1 endwhile\nM2\n",
      "G21 G0 X0 Y0 Z10\nG81 X5 Y5 Z-2 R2 F100\nX10\nG80\nG4 P1\nM2\n",
  };
  for (const std::string& program : programs) {
    std::istringstream in(program);
    std::size_t calls = 0;
    const abbe::gcode::ProgramStats stats =
        abbe::gcode::run_program(in, "t.ngc", InterpreterConfig{}, [&](const Motion&) { ++calls; });
    EXPECT_GT(calls, 3u) << program;
    EXPECT_EQ(stats.motions, calls) << program;
  }
}

}  // namespace
