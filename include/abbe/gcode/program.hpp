#pragma once
// Streams a whole NC program through parser and interpreter: each line is
// parsed, executed, and its motions handed to `sink`, one block at a time.
#include <istream>
#include <string>

#include "abbe/gcode/interpreter.hpp"

namespace abbe::gcode {

struct ProgramStats {
  std::size_t lines = 0;
  std::size_t motions = 0;
};

// Throws abbe::InputError (file:line:col) on the first bad block.
ProgramStats run_program(std::istream& in, const std::string& file, const InterpreterConfig& config,
                         const MotionSink& sink);

}  // namespace abbe::gcode
