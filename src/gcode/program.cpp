#include "abbe/gcode/program.hpp"

#include "abbe/gcode/parser.hpp"
#include "fanuc_program.hpp"

namespace abbe::gcode {

ProgramStats run_program(std::istream& in, const std::string& file, const InterpreterConfig& config,
                         const MotionSink& sink) {
  if (config.dialect.dialect == Dialect::fanuc)
    return detail::run_fanuc_program(in, file, config, sink);
  ProgramStats stats;
  BlockReader reader(in, file);
  Interpreter interpreter(config, file);
  Block block;
  const MotionSink counting_sink = [&](const Motion& m) {  // built once, not per block
    ++stats.motions;
    sink(m);
  };
  while (!interpreter.program_ended() && reader.next(block)) {
    ++stats.lines;
    interpreter.execute(block, reader.line_text(), counting_sink);
  }
  return stats;
}

}  // namespace abbe::gcode
