#include "abbe/pipeline/interpreter_setup.hpp"

#include "abbe/machine/home_positions.hpp"

namespace abbe::pipeline {

gcode::InterpreterConfig interpreter_config(const machine::Machine& machine) {
  gcode::InterpreterConfig config;
  config.default_tool_length = machine.tool_length();
  config.tool_lengths = machine.tool_table();
  config.tool_diameters = machine.tool_diameters();
  config.work_offsets = machine.work_offsets();
  config.initial_position = Eigen::Vector3d(0.0, 0.0, -machine.tool_length());
  const machine::HomePositions home = machine::read_home_positions(machine.spec().file);
  config.g28_position = home.g28;
  config.g30_position = home.g30;
  return config;
}

}  // namespace abbe::pipeline
