#include "abbe/gcode/program.hpp"

#include "fanuc_program.hpp"
#include "program_runner.hpp"

namespace abbe::gcode {

ProgramStats run_program(std::istream& in, const std::string& file, const InterpreterConfig& config,
                         const MotionSink& sink) {
  if (config.dialect.dialect == Dialect::fanuc)
    return detail::run_fanuc_program(in, file, config, sink);
  // Plain blocks stream straight through; parameters, expressions and
  // O-words are evaluated there (src/gcode/program_runner.cpp).
  return detail::run_rs274_program(in, file, config, sink);
}

}  // namespace abbe::gcode
