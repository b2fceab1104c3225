#pragma once
// Runs a LinuxCNC-dialect program with parameters, expressions and O-word
// control flow between the block reader and the interpreter.
#include <istream>
#include <string>

#include "abbe/gcode/program.hpp"

namespace abbe::gcode::detail {

ProgramStats run_rs274_program(std::istream& in, const std::string& file,
                               const InterpreterConfig& config, const MotionSink& sink);

}  // namespace abbe::gcode::detail
