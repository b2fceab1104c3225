// The interpreter's plain-block path (a block with no G code but a motion
// code, no M code, and only X Y Z F S T words for G0/G1 or X Y Z I J K R P
// F S T for G2/G3, goes from its end point to the sink without the mode
// steps) must give exactly what the general path gives. The general
// path is forced by adding G97 to every block: a code of its own modal group
// (spindle speed mode) that changes no motion, so the block is no longer
// plain but means the same. Motions are compared field by field, bit for
// bit, and a refused program must be refused with the same message.
#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "abbe/gcode/interpreter.hpp"
#include "abbe/gcode/parser.hpp"
#include "abbe/io/input_error.hpp"

namespace abbe::gcode {
namespace {

namespace fs = std::filesystem;

struct ProgramRun {
  std::vector<Motion> motions;
  std::string error;  // empty: the program ran to its end
};

bool has_g97(const Block& block) {
  for (const Word& w : block.words)
    if (w.letter == 'G' && std::abs(w.value - 97.0) < 1e-9) return true;
  return false;
}

// Runs the program block by block; `force_general` adds G97 to every block
// that has words.
ProgramRun run(const std::string& text, bool force_general) {
  ProgramRun out;
  std::istringstream in(text);
  BlockReader reader(in, "plain-path.ngc");
  Interpreter interp(InterpreterConfig{}, "plain-path.ngc");
  const auto sink = [&](const Motion& m) { out.motions.push_back(m); };
  Block block;
  try {
    while (!interp.program_ended() && reader.next(block)) {
      if (force_general && !block.words.empty() && !has_g97(block)) {
        Word g97;
        g97.letter = 'G';
        g97.value = 97.0;
        g97.begin = g97.number_begin = g97.end =
            static_cast<std::uint32_t>(reader.line_text().size());
        block.words.push_back(g97);
      }
      interp.execute(block, reader.line_text(), sink);
    }
    interp.finish(sink);
  } catch (const InputError& e) {
    out.error = e.what();
  }
  return out;
}

void expect_same_vector(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const char* what,
                        std::size_t i) {
  for (int k = 0; k < 3; ++k) EXPECT_EQ(a[k], b[k]) << what << "[" << k << "] of motion " << i;
}

void expect_same_runs(const ProgramRun& plain, const ProgramRun& general, const std::string& name) {
  SCOPED_TRACE(name);
  EXPECT_EQ(plain.error, general.error);
  ASSERT_EQ(plain.motions.size(), general.motions.size());
  for (std::size_t i = 0; i < plain.motions.size(); ++i) {
    const Motion& p = plain.motions[i];
    const Motion& g = general.motions[i];
    EXPECT_EQ(p.kind, g.kind) << "motion " << i;
    EXPECT_EQ(p.line, g.line) << "motion " << i;
    EXPECT_EQ(p.sub, g.sub) << "motion " << i;
    expect_same_vector(p.start, g.start, "start", i);
    expect_same_vector(p.end, g.end, "end", i);
    expect_same_vector(p.center, g.center, "center", i);
    EXPECT_EQ(p.plane, g.plane) << "motion " << i;
    EXPECT_EQ(p.rotation, g.rotation) << "motion " << i;
    EXPECT_EQ(p.feed, g.feed) << "motion " << i;
    EXPECT_EQ(p.dwell_seconds, g.dwell_seconds) << "motion " << i;
    // NaN (tool length unknown) compares unequal to itself: compare bits.
    EXPECT_TRUE(p.tool_length == g.tool_length ||
                (std::isnan(p.tool_length) && std::isnan(g.tool_length)))
        << "motion " << i;
    EXPECT_EQ(p.spindle, g.spindle) << "motion " << i;
    EXPECT_EQ(p.tool, g.tool) << "motion " << i;
  }
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A random program of straight moves (absolute and incremental, explicit
// and modal), arcs with exact end points, feed, speed and tool words, and
// blocks with other codes in between.
std::string random_program(unsigned seed, int blocks) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> coord(-200.0, 200.0);
  std::uniform_real_distribution<double> step(-20.0, 20.0);
  std::uniform_real_distribution<double> angle(0.2, 5.5);
  std::uniform_int_distribution<int> pick(0, 15);
  std::ostringstream out;
  out.precision(6);
  out << std::fixed;
  out << "G17 G21 G90 G94\nG0 X0 Y0 Z0\nF800\n";
  double x = 0, y = 0;
  bool incremental = false;
  int motion = 0;
  for (int i = 0; i < blocks; ++i) {
    const int k = pick(rng);
    if (k < 5) {  // a straight move, explicit code or modal
      const double nx = incremental ? step(rng) : coord(rng);
      const double ny = incremental ? step(rng) : coord(rng);
      if (k < 3 || motion > 1) {
        motion = k % 2;
        out << "G" << motion << " ";
      }
      out << "X" << nx << " Y" << ny;
      if (k == 4) out << " Z" << (incremental ? step(rng) : coord(rng) / 4);
      if (k == 2) out << " F" << 100 + 10 * (i % 50);
      out << "\n";
      x = incremental ? x + nx : nx;
      y = incremental ? y + ny : ny;
    } else if (k < 8 && !incremental) {  // an arc about an offset centre, exact end
      const double i_off = step(rng), j_off = step(rng);
      const double cx = x + i_off, cy = y + j_off;
      const double a = angle(rng) * (k == 5 ? -1.0 : 1.0);
      const double ex = cx + (x - cx) * std::cos(a) - (y - cy) * std::sin(a);
      const double ey = cy + (x - cx) * std::sin(a) + (y - cy) * std::cos(a);
      motion = a < 0 ? 2 : 3;
      out << "G" << motion << " X" << ex << " Y" << ey << " I" << i_off << " J" << j_off << "\n";
      x = ex;
      y = ey;
    } else if (k == 8) {
      out << "S" << 1000 + i << " T" << (i % 7) << "\n";
    } else if (k == 9) {
      incremental = !incremental;
      out << (incremental ? "G91" : "G90") << "\n";
    } else if (k == 10) {
      const double nx = incremental ? step(rng) : coord(rng);
      out << "G1 X" << nx << " F" << 200 + i % 300 << " M8\n";
      x = incremental ? x + nx : nx;
      motion = 1;
    } else if (k == 11) {
      out << "(a comment) F" << 300 + i % 100 << "\n";
    } else if (k == 12) {
      out << "G4 P0.1\n";
    } else {  // a modal straight move (after an arc: an explicit G1)
      const double nx = incremental ? step(rng) : coord(rng);
      if (motion > 1) {
        motion = 1;
        out << "G1 ";
      }
      out << "X" << nx << "\n";
      x = incremental ? x + nx : nx;
    }
  }
  out << "M2\n";
  return out.str();
}

TEST(InterpreterPlainPath, SameMotionsAsTheGeneralPathOnTheBundledSamples) {
  int files = 0;
  for (const auto& dir :
       {fs::path(ABBE_SOURCE_DIR) / "nc-samples", fs::path(ABBE_TEST_DATA_DIR) / "cam-corpus"}) {
    for (const auto& entry : fs::directory_iterator(dir)) {
      const std::string ext = entry.path().extension().string();
      if (ext != ".ngc" && ext != ".nc" && ext != ".gcode" && ext != ".tap") continue;
      const std::string text = read_file(entry.path());
      const ProgramRun plain = run(text, false);
      const ProgramRun general = run(text, true);
      expect_same_runs(plain, general, entry.path().filename().string());
      ++files;
    }
  }
  EXPECT_GE(files, 20);
}

TEST(InterpreterPlainPath, SameMotionsAsTheGeneralPathOnRandomPrograms) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const std::string text = random_program(seed, 400);
    const ProgramRun plain = run(text, false);
    const ProgramRun general = run(text, true);
    EXPECT_TRUE(plain.error.empty()) << plain.error;
    ASSERT_GT(plain.motions.size(), 100u);
    expect_same_runs(plain, general, "seed " + std::to_string(seed));
  }
}

TEST(InterpreterPlainPath, SameMotionsAndRefusalsOnArcBlocks) {
  // Arcs in every plane and format, modal and explicit, with turns, in
  // inverse time and incremental centres, and the arc words' refusals.
  const std::vector<std::string> programs = {
      "G0 X0 Y0 Z0\nG2 X10 Y0 R5 F100\nG3 X0 Y0 R-5\n",
      "G0 X0 Y0 Z0\nG2 X10 Y0 I5 J0 F100\nX0 Y0 I-5 J0\nG3 X10 Y0 I5 J0 Z-2 S900 T2\n",
      "G0 X0 Y0 Z0\nG2 X10 Y0 I5 J0 P3 F100\n",
      "G0 X0 Y0 Z0\nG3 I5 J0 F100\n",
      "G18 G0 X0 Y0 Z0\nG2 X10 Z0 I5 K0 F100\nG19 G3 Y10 Z0 J5 K0\n",
      "G91.1 G0 X0 Y0 Z0\nG90.1 G2 X10 Y0 I5 J0 F100\nG91.1 G2 X0 Y0 I-5 J0\n",
      "G91 G0 X1 Y1 Z1\nG2 X10 Y0 I5 J0 F100\nG3 X-10 Y0 R5\n",
      "G0 X0 Y0 Z0\nG93\nG2 X10 Y0 I5 J0 F2\nG3 X0 Y0 I-5 J0 F3\n",
      "G20 G0 X0 Y0 Z0\nG2 X1 Y0 I0.5 J0 F10\n",
      "G0 X0 Y0 Z0\nG1 X5 I3 F100\n",
      "G0 X0 Y0 Z0\nG1 X5 F100\nX6 R2\n",
      "G0 X0 Y0 Z0\nG2 X10 Y0 R5 I5 F100\n",
      "G0 X0 Y0 Z0\nG2 X10 Y0 I5 K1 F100\n",
      "G0 X0 Y0 Z0\nG2 X10 Y0 F100\n",
      "G0 X0 Y0 Z0\nG2 X10 Y0 I5 J0 P0.5 F100\n",
      "G0 X0 Y0 Z0\nG2 X10 Y0 I5 J0 F100\nI5 J0\n",
      "G0 X0 Y0 Z0\nG2 X10 Y0 I5 J0\n",
      "G0 X0 Y0 Z0\nG2 X10 Y0 I3 J0 F100\n",
      "G0 X0 Y0 Z0\nG2 X10 Y0 R2 F100\n",
      "G0 X0 Y0 Z0\nG0 X10 Y0 I5\n",
      "G0 X0 Y0 Z0\nG2 X100000000 Y0 I50000000 J0 F100\n",
      "G0 X-9 F1\nG41.1 D4 G1 X0\nG40\nG2 X1 Y1 R1\n",
      "G0 X-9 Y-10 F1\nG41.1 D4 G1 X0 Y0\nG3 X10 Y0 I5 J0\nG40 G1 X20\nG3 X10 Y0 R5\n",
  };
  int refused = 0;
  for (const std::string& text : programs) {
    const ProgramRun plain = run(text, false);
    const ProgramRun general = run(text, true);
    expect_same_runs(plain, general, text);
    refused += !plain.error.empty();
  }
  EXPECT_GE(refused, 10);  // the refusals above are compared, not only the motions
}

TEST(InterpreterPlainPath, TheComparisonSeesADifference) {
  // The check itself fails on runs that differ in one feed rate.
  static const ProgramRun a = run("G0 X0 Y0 Z0\nG1 X10 F100\n", false);
  static const ProgramRun b = run("G0 X0 Y0 Z0\nG1 X10 F200\n", false);
  EXPECT_NONFATAL_FAILURE(expect_same_runs(a, b, "feeds differ"), "feed");
}

}  // namespace
}  // namespace abbe::gcode
