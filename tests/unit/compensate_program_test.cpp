// compensate_program + verify_program on the nc-samples, a G91/G18/G19 test
// program and a generated program: zero tables give the input byte for byte;
// the sample machine's compensated programs are predicted within tol of the
// nominal path; everything but the coordinates is kept.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>

#include "abbe/compensate/path_verifier.hpp"
#include "abbe/compensate/program_compensator.hpp"
#include "abbe/gcode/program.hpp"
#include "abbe/io/input_error.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/pipeline/interpreter_setup.hpp"
#include "tools/gen/program_generator.hpp"

namespace abbe::compensate {
namespace {

const std::string kSamples = std::string(ABBE_SOURCE_DIR) + "/nc-samples/";
const std::string kSample = std::string(ABBE_SOURCE_DIR) + "/machines/sample/machine.yaml";
const std::string kZero = std::string(ABBE_TEST_DATA_DIR) + "/compensate/zero.yaml";
const std::string kG91 = std::string(ABBE_TEST_DATA_DIR) + "/compensate/g91-g18-g19.ngc";

const std::vector<std::string> kFiles = {
    "drilling.ngc",           "helix-g18-g19.ngc",     "inch-r-arcs.ngc",      "spline-slot.ngc",
    "spline-slot-corner.ngc", "thesis-toolpath-1.ngc", "thesis-toolpath-2.ngc"};

std::string read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  EXPECT_TRUE(in) << path;
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

gcode::InterpreterConfig config_of(const machine::Machine& m) {
  return pipeline::interpreter_config(m);
}

struct Compensated {
  std::string text;
  CompensateSummary summary;
};

Compensated compensate_text(const std::string& program, const std::string& name,
                            const std::string& machine, const CompensateOptions& o = {}) {
  const machine::Machine m = machine::Machine::load(machine);
  const model::ErrorModel em(m, model::ModelKind::ae_arm);
  std::istringstream in(program);
  Compensated r;
  r.summary = compensate_program(in, name, config_of(m), em, o,
                                 [&](const char* d, std::size_t n) { r.text.append(d, n); });
  return r;
}

VerifyStats verify_text(const std::string& compensated, const std::string& original,
                        const std::string& machine) {
  const machine::Machine m = machine::Machine::load(machine);
  const model::ErrorModel em(m, model::ModelKind::ae_arm);
  std::istringstream c(compensated), o(original);
  return verify_program(c, "out.nc", o, "in.nc", config_of(m), em, VerifyOptions{});
}

// A line without its coordinate words (X Y Z I J K R P L and their numbers,
// outside comments): what must be the same in input and output. (An L word
// goes only where a G91 G98 canned cycle is expanded, checked below.)
std::string skeleton(const std::string& line) {
  std::string out;
  int depth = 0;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char ch = line[i];
    if (ch == ';' && depth == 0) {
      out.append(line, i, std::string::npos);
      break;
    }
    if (ch == '(') ++depth;
    if (ch == ')') --depth;
    if (depth == 0 && std::string("XYZIJKRPLxyzijkrpl").find(ch) != std::string::npos) {
      std::size_t j = i + 1;
      while (j < line.size() && std::string("+-.0123456789").find(line[j]) != std::string::npos)
        ++j;
      if (!out.empty() && out.back() == ' ') out.pop_back();
      i = j - 1;
      continue;
    }
    out.push_back(ch);
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> v;
  std::istringstream s(text);
  for (std::string l; std::getline(s, l);) v.push_back(l);
  return v;
}

// The skeleton without a G2/G3 word: an arc block that relies on the modal
// G2/G3 gets the word when a micro move (G1) is written before it.
std::string without_arc_word(std::string s) {
  for (const char* w : {"G2 ", "G3 ", "G2", "G3"}) {
    const auto p = s.find(w);
    if (p != std::string::npos) return s.erase(p, std::string(w).size());
  }
  return s;
}

// An inserted line: coordinate words, with G1 (a micro move) or G2/G3 (an
// arc piece after one) at most.
bool inserted(const std::string& line) {
  const std::string k = skeleton(line);
  return !line.empty() && (k.empty() || k == "G1" || k == "G2" || k == "G3");
}

// Every input line appears in order in the output with the same skeleton;
// the output lines in between are inserted pieces.
void expect_kept(const std::string& in, const std::string& out, const std::string& name) {
  const auto a = lines_of(in), b = lines_of(out);
  std::size_t j = 0;
  for (std::size_t i = 0; i < a.size(); ++i, ++j) {
    const std::string want = skeleton(a[i]);
    while (j < b.size() && skeleton(b[j]) != want && without_arc_word(skeleton(b[j])) != want &&
           inserted(b[j]))
      ++j;
    ASSERT_LT(j, b.size()) << name << ": output ends before input line " << i + 1;
    EXPECT_TRUE(skeleton(b[j]) == want || without_arc_word(skeleton(b[j])) == want)
        << name << ": input line " << i + 1 << " \"" << a[i] << "\" vs \"" << b[j] << "\"";
  }
  for (; j < b.size(); ++j) EXPECT_TRUE(inserted(b[j])) << name << ": trailing line " << b[j];
}

TEST(CompensateProgram, ZeroTablesGiveTheInputByteForByte) {
  for (const auto& f : kFiles) {
    const std::string in = read(kSamples + f);
    const Compensated r = compensate_text(in, f, kZero);
    EXPECT_EQ(r.text, in) << f;
    EXPECT_EQ(r.summary.blocks_changed, 0u) << f;
    EXPECT_GT(r.summary.points, 0u) << f;
  }
  const std::string g91 = read(kG91);
  EXPECT_EQ(compensate_text(g91, "g91", kZero).text, g91);
}

TEST(CompensateProgram, SamplesAreWithinTolAfterCompensation) {
  for (const auto& f : kFiles) {
    const std::string in = read(kSamples + f);
    const Compensated r = compensate_text(in, f, kSample);
    EXPECT_GT(r.summary.blocks_changed, 0u) << f;
    EXPECT_EQ(r.summary.unconverged_points, 0u) << f;
    const VerifyStats before = verify_text(in, in, kSample);
    const VerifyStats after = verify_text(r.text, in, kSample);
    EXPECT_LE(after.max_um, 1.0) << f;
    EXPECT_LE(after.backward_max_um, 1.0) << f;
    EXPECT_EQ(after.over_tol + after.backward_over_tol, 0u) << f;
    EXPECT_GT(before.max_um, 5.0) << f;  // there was something to compensate
    EXPECT_LT(after.rms_um, 0.2 * before.rms_um) << f;
    expect_kept(in, r.text, f);
  }
}

TEST(CompensateProgram, IncrementalArcsInAllPlanes) {
  const std::string in = read(kG91);
  const Compensated r = compensate_text(in, "g91", kSample);
  const VerifyStats after = verify_text(r.text, in, kSample);
  EXPECT_LE(after.max_um, 1.0);
  EXPECT_LE(after.backward_max_um, 1.0);
  expect_kept(in, r.text, "g91");
  // Increments stay increments: the X of N70 (the first of its pieces) is
  // positive and at most about 100.
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.text, m, std::regex("N70 X([-0-9.]+)")));
  EXPECT_GT(std::stod(m[1]), 0.0);
  EXPECT_LT(std::stod(m[1]), 100.05);
  EXPECT_NE(m[1], "100");
  // No N numbers on inserted pieces unless --renumber: the lines without one
  // are pieces (coordinates, G1 micro moves, G2/G3 arc pieces after them).
  for (const auto& l : lines_of(r.text))
    if (!l.empty() && l[0] != '(' && l[0] != 'N') {
      EXPECT_TRUE(inserted(l)) << l;
    }
}

TEST(CompensateProgram, InchProgramStaysInInches) {
  const std::string in = read(kSamples + "inch-r-arcs.ngc");
  const Compensated r = compensate_text(in, "inch", kSample);
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.text, m, std::regex("\nG0 X(-[0-9.]+) Y(-[0-9.]+)")));
  EXPECT_NEAR(std::stod(m[1]), -20.0, 0.002);  // inches, not -508 mm
  EXPECT_NE(m[1], "-20");
  // Five decimals at most in inch (0.25 µm), at least the number's own.
  EXPECT_LE(m[1].str().size() - m[1].str().find('.') - 1, 5u);
}

TEST(CompensateProgram, DecimalsOption) {
  const std::string in = read(kSamples + "thesis-toolpath-1.ngc");
  CompensateOptions o;
  o.decimals = 6;
  const Compensated r = compensate_text(in, "t1", kSample, o);
  EXPECT_TRUE(std::regex_search(r.text, std::regex("X-[0-9]+\\.[0-9]{5,6}\\b")));
  o.decimals = 3;
  const Compensated r3 = compensate_text(in, "t1", kSample, o);
  EXPECT_FALSE(std::regex_search(r3.text, std::regex("[XYZ]-?[0-9]+\\.[0-9]{4}")));
}

TEST(CompensateProgram, RefusesABadProgramWithTheFrontEndsMessage) {
  const std::string bad = "G21 G90\nG1 X10 F100\nG2 X20 Y5\n";  // an arc without a centre
  std::string front, here;
  try {
    std::istringstream in(bad);
    gcode::InterpreterConfig c;
    gcode::run_program(in, "bad.nc", c, [](const gcode::Motion&) {});
  } catch (const InputError& e) {
    front = e.what();
  }
  try {
    compensate_text(bad, "bad.nc", kSample);
  } catch (const InputError& e) {
    here = e.what();
  }
  ASSERT_FALSE(front.empty());
  EXPECT_EQ(here, front);
}

TEST(CompensateProgram, RefusesBackBoringByName) {
  // G87's K level would stay nominal: refused at the block, not half-corrected.
  const std::string g87 =
      "G21 G90\nG0 X-100 Y-100 Z-200 F100 S1000 M3\nG87 X-101 Y-101 Z-210 R-195 I0.5 J0.25 "
      "K-205\nG80\nM2\n";
  try {
    compensate_text(g87, "g87.nc", kSample);
    FAIL() << "G87 was compensated";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().line, 3u);
    EXPECT_NE(std::string(e.what()).find("back boring (G87) is not compensated"),
              std::string::npos);
  }
}

TEST(CompensateProgram, RefusesABlockOverThePointBudgetAtItsLine) {
  // A drilling cycle repeated 400 times: 400 holes of 7 mm depth, two points
  // each at step 5 mm (plus the moves between them) is over a budget of 1000
  // points; with the budget raised it is compensated.
  const std::string program =
      "G21 G90\nG0 X-100 Y-100 Z-200 F100 S1000 M3\nG91 G81 X0.1 Y0 Z-5 R-2 L400\nG80\nM2\n";
  CompensateOptions o;
  o.max_block_points = 1000;
  try {
    compensate_text(program, "many.nc", kSample, o);
    FAIL() << "a block over the point budget was compensated";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().line, 3u);
    EXPECT_NE(std::string(e.what()).find("more than 1000 path points"), std::string::npos)
        << e.what();
  }
  o.max_block_points = 100'000;
  EXPECT_EQ(lines_of(compensate_text(program, "many.nc", kSample, o).text).size(), 5u);
}

// 2 000 blocks keep the Debug test short; a 4 000-block run is in
// tests/cli/compensate.cmake (cli_compensate_generated), 1 M blocks in
// docs/compensation.md.
TEST(CompensateProgram, GeneratedProgram) {
  gen::ProgramGenerator g(11);
  fmt::memory_buffer buf;
  std::string program;
  g.write(2000, buf, [&](fmt::memory_buffer& b) {
    program.append(b.data(), b.size());
    b.clear();
  });
  const Compensated zero = compensate_text(program, "gen", kZero);
  EXPECT_EQ(zero.text, program);
  const Compensated r = compensate_text(program, "gen", kSample);
  EXPECT_EQ(r.summary.unconverged_points, 0u);
  const VerifyStats after = verify_text(r.text, program, kSample);
  EXPECT_GT(after.points, 2000u);
  EXPECT_LE(after.rms_um, 0.25);
  EXPECT_LE(after.max_um, 1.0);
  EXPECT_LE(after.backward_max_um, 1.0);
  EXPECT_EQ(after.over_tol + after.backward_over_tol, 0u);
  expect_kept(program, r.text, "generated");
}

// The sample machine's Z axis has 15.5 µm between its forward and reverse
// positioning tables: where Z reverses — at the bottom and top of a G19 arc,
// at a corner — the correction jumps. Compensate takes each jump by a micro
// move (G1) at the reversal point; the arc pieces after it name their G2/G3.
TEST(CompensateProgram, ReversalJumpsAreTakenByMicroMoves) {
  const std::string in =
      "G17 G21 G90 G94\nG54\nG0 X-313.4331 Y-280 Z-385.8720\nG1 Y-285.2984 F1500\n"
      "G19 G3 Y-287.0931 Z-380.0706 J3.9599 K4.4033\n"  // Z reverses at the bottom and top
      "X-315 Y-291.0931 J-2 K0\n"                       // a modal G3 (helix)
      "G1 Z-370\nZ-380\n"                               // Z reverses at the corner
      "G18 G2 X-320 Z-380 I-2.5 K0\nM30\n";
  const Compensated r = compensate_text(in, "rev", kSample);
  const VerifyStats before = verify_text(in, in, kSample);
  const VerifyStats after = verify_text(r.text, in, kSample);
  EXPECT_GT(before.max_um, 10.0);
  EXPECT_LE(after.max_um, 1.0);
  EXPECT_LE(after.backward_max_um, 1.0);
  expect_kept(in, r.text, "rev");
  // Micro moves were written: G1 lines of coordinates only.
  std::size_t micro = 0;
  for (const auto& l : lines_of(r.text))
    if (skeleton(l) == "G1") ++micro;
  EXPECT_GE(micro, 3u) << r.text;
}

// A G91 G98 canned cycle with L repeats is expanded: one block per hole (the
// L word goes, the other holes are inserted lines of increments), so that
// every hole gets its own correction.
TEST(CompensateProgram, RepeatedIncrementalCycleIsExpanded) {
  const std::string in = read(kSamples + "drilling.ngc");
  const Compensated r = compensate_text(in, "drilling", kSample);
  EXPECT_EQ(r.text.find("L5"), std::string::npos);
  const auto out = lines_of(r.text);
  std::size_t at = 0;
  for (std::size_t i = 0; i < out.size(); ++i)
    if (out[i].rfind("G91 G98 G81", 0) == 0) at = i;
  ASSERT_GT(at, 0u);
  // Four inserted lines of X, Y increments (and Z where the depth changes).
  // An increment whose correction change rounds away is written without
  // decimals.
  for (std::size_t k = 1; k <= 4; ++k) {
    ASSERT_LT(at + k, out.size());
    EXPECT_TRUE(
        std::regex_match(out[at + k], std::regex("X-1[45](\\.[0-9]+)? Y-?[0-9.]+( Z-[0-9.]+)?")))
        << out[at + k];
  }
  const VerifyStats after = verify_text(r.text, in, kSample);
  EXPECT_LE(after.max_um, 1.0);
  EXPECT_LE(after.backward_max_um, 1.0);
  // The expanded program drills the same holes as the original (zero tables
  // leave L5 as it is, so compare against the nominal interpretation).
  const machine::Machine m = machine::Machine::load(kSample);
  std::vector<Eigen::Vector3d> a, b;
  auto bottoms = [&](const std::string& text, std::vector<Eigen::Vector3d>& v) {
    std::istringstream s(text);
    gcode::run_program(s, "d", config_of(m), [&](const gcode::Motion& x) {
      if (x.kind == gcode::MotionKind::linear && x.line >= 39) v.push_back(x.end);
    });
  };
  bottoms(in, a);
  bottoms(r.text, b);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_LT((a[i] - b[i]).norm(), 0.05) << i;
}

}  // namespace
}  // namespace abbe::compensate
