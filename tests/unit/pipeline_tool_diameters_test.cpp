// The machine file's tool_diameters reach cutter radius compensation through
// pipeline::interpreter_config: a G41 program runs with the machine file
// alone, its tool-centre path offset by the radius, and the same program
// without a diameter is refused.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <sstream>

#include "abbe/io/input_error.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/pipeline/interpreter_setup.hpp"
#include "abbe/pipeline/program_path.hpp"

namespace abbe::pipeline {
namespace {

const std::string kDir = std::string(ABBE_TEST_DATA_DIR) + "/machines";

machine::Machine sample_with(const std::string& extra) {
  std::ifstream in(kDir + "/sample.yaml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return machine::Machine::parse(text + extra, "m.yaml", kDir);
}

// The tool tip where line 4 (the move along +Y) ends.
Eigen::Vector3d end_of_line_4(const machine::Machine& m, const std::string& program) {
  std::istringstream in(program);
  Eigen::Vector3d end = Eigen::Vector3d::Constant(1e9);
  run_path(in, "t.ngc", interpreter_config(m), PathOptions{}, [&](const path::PathPoint& p) {
    if (p.line == 4) end = p.p;
  });
  return end;
}

const std::string kPlain = "G21 G0 X-10 Y-10 Z0 F100\nT1 M6\nG1 X0 Y0\nY10\nM2\n";
const std::string kLeft = "G21 G0 X-10 Y-10 Z0 F100\nT1 M6\nG41 G1 X0 Y0\nY10\nG40 X-10\nM2\n";

TEST(ToolDiameters, MachineFileGivesTheCutterRadius) {
  const machine::Machine m = sample_with("tool_diameters:\n  1: 4.0\n");
  EXPECT_EQ(interpreter_config(m).tool_diameters.at(1), 4.0);
  const Eigen::Vector3d plain = end_of_line_4(m, kPlain);
  const Eigen::Vector3d left = end_of_line_4(m, kLeft);
  // G41 going +Y: the tool centre runs radius 2 mm to the left (−X).
  EXPECT_NEAR(left.x() - plain.x(), -2.0, 1e-9);
  EXPECT_NEAR(left.y() - plain.y(), 0.0, 1e-9);
  EXPECT_NEAR(left.z() - plain.z(), 0.0, 1e-12);
}

TEST(ToolDiameters, WithoutADiameterG41IsRefused) {
  const machine::Machine m = sample_with("");
  EXPECT_TRUE(interpreter_config(m).tool_diameters.empty());
  try {
    end_of_line_4(m, kLeft);
    FAIL() << "G41 without a tool diameter was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().line, 3u) << e.what();
  }
}

}  // namespace
}  // namespace abbe::pipeline
