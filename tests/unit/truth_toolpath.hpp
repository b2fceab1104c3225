#pragma once
// The fragmented toolpath of a bundled NC sample, set up as a virtual
// machine's truth file says (tool table, default tool length, start with
// the spindle at home): the points the truth-comparison tests predict.
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "abbe/gcode/program.hpp"
#include "abbe/path/fragmenter.hpp"
#include "abbe/sim/truth_machine.hpp"

namespace abbe::test {

inline std::vector<path::PathPoint> truth_toolpath(const std::string& sample,
                                                   const sim::TruthMachine& truth) {
  gcode::InterpreterConfig config;
  config.tool_lengths = truth.tool_table;
  config.default_tool_length = truth.tool_length;
  config.initial_position = Eigen::Vector3d(0.0, 0.0, -truth.tool_length);
  const std::string path = std::string(ABBE_SOURCE_DIR) + "/nc-samples/" + sample;
  std::ifstream in(path);
  EXPECT_TRUE(in) << path;
  path::Fragmenter fragmenter(path::FragmentOptions{});
  std::vector<path::PathPoint> points;
  gcode::run_program(in, path, config, [&](const gcode::Motion& m) {
    fragmenter.add(m, [&](const path::PathPoint& p) { points.push_back(p); });
  });
  return points;
}

}  // namespace abbe::test
