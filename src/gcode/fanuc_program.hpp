#pragma once
// Runs a Fanuc/Haas-style program (private to the library): the file's
// O-numbered programs are held in memory — a subprogram usually follows the
// main program's M30 — and M98 P… L… / M99 are followed between them.
#include <istream>
#include <string>

#include "abbe/gcode/interpreter.hpp"
#include "abbe/gcode/program.hpp"

namespace abbe::gcode::detail {

// At most this many subprogram levels (Fanuc 0i/30i allow 10 M98 levels).
inline constexpr std::size_t kMaxSubprogramNesting = 10;
// Repeat counts multiply: a bound on executed blocks keeps a program with
// nested L9999 calls from running for hours (a clear error instead).
inline constexpr std::size_t kMaxExecutedBlocks = 100'000'000;

ProgramStats run_fanuc_program(std::istream& in, const std::string& file,
                               const InterpreterConfig& config, const MotionSink& sink);

}  // namespace abbe::gcode::detail
