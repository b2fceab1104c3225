#include "abbe/pipeline/interpreter_setup.hpp"

namespace abbe::pipeline {

gcode::InterpreterConfig interpreter_config(const machine::Machine& machine) {
  gcode::InterpreterConfig config;
  config.default_tool_length = machine.tool_length();
  config.tool_lengths = machine.tool_table();
  config.work_offsets = machine.work_offsets();
  config.initial_position = Eigen::Vector3d(0.0, 0.0, -machine.tool_length());
  return config;
}

}  // namespace abbe::pipeline
