#include "fanuc_program.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <map>
#include <vector>

#include "abbe/gcode/modal_groups.hpp"
#include "abbe/gcode/parser.hpp"
#include "abbe/io/input_error.hpp"
#include "fanuc_dialect.hpp"

namespace abbe::gcode::detail {

namespace {

struct StoredLine {
  std::string text;
  std::size_t number = 0;      // 1-based line in the file
  bool program_start = false;  // an O-number line
};

// A running subprogram: where its body begins, how many more times it runs,
// and the line after its M98.
struct Frame {
  std::size_t body = 0;
  long remaining = 0;
  std::size_t return_to = 0;
};

}  // namespace

ProgramStats run_fanuc_program(std::istream& in, const std::string& file,
                               const InterpreterConfig& config, const MotionSink& sink) {
  // Read: every line, and where each O-numbered program begins. A '%' after
  // the program text ends the file (the tape's end), as on the control.
  std::vector<StoredLine> lines;
  std::map<long, std::size_t> programs;  // program number -> index of its O line
  {
    BlockReader reader(in, file);
    Block block;
    bool text_seen = false;
    while (reader.next(block)) {
      if (block.percent) {
        if (text_seen) break;
      } else if (!block.words.empty() || block.program_number) {
        text_seen = true;
      }
      StoredLine line{std::string(reader.line_text()), block.line, false};
      if (block.program_number) {
        line.program_start = true;
        if (!programs.emplace(*block.program_number, lines.size()).second)
          throw InputError(SourceLocation{file, block.line, 1, "", line.text},
                           fmt::format("program number O{} is defined twice in this file",
                                       *block.program_number));
      }
      lines.push_back(std::move(line));
    }
  }

  ProgramStats stats;
  Interpreter interpreter(config, file);
  const MotionSink counting_sink = [&](const Motion& m) {
    ++stats.motions;
    sink(m);
  };
  std::vector<Frame> calls;
  bool main_started = false;  // the first O line (or the first block) begins the main program
  Block block;
  std::size_t pc = 0;
  while (pc < lines.size() && !interpreter.program_ended()) {
    const StoredLine& line = lines[pc];
    const BlockContext ctx{file, line.number, line.text};
    if (line.program_start) {
      if (main_started && calls.empty()) break;  // the main program ends where the next begins
      if (main_started)
        throw InputError(SourceLocation{file, line.number, 1, "", line.text},
                         "a subprogram runs into the next program without M99");
    }
    parse_line(line.text, line.number, file, block);
    if (!block.words.empty() || line.program_start) main_started = true;
    if (++stats.lines > kMaxExecutedBlocks)
      throw InputError(SourceLocation{file, line.number, 1, "", line.text},
                       fmt::format("more than {} blocks executed: the subprogram repeat counts "
                                   "(M98 L) multiply beyond what abbe follows",
                                   kMaxExecutedBlocks));
    const FanucFlow flow = fanuc_flow(block, ctx);
    // execute() refuses macro variables and expressions by name; the rest
    // runs like the LinuxCNC dialect's blocks (cutter radius compensation
    // included, which line-by-line rewriting refuses).
    if (block.has_code())
      interpreter.execute(block, line.text, counting_sink);
    else
      interpreter.execute_evaluated(block, line.text, counting_sink);
    if (interpreter.program_ended()) break;
    if (flow.call) {
      const auto called = programs.find(*flow.call);
      if (called == programs.end())
        ctx.fail(flow.at, fmt::format("subprogram O{} is not in this file", *flow.call));
      if (calls.size() >= kMaxSubprogramNesting)
        ctx.fail(flow.at,
                 fmt::format("subprograms nested deeper than {} levels", kMaxSubprogramNesting));
      if (flow.repeats == 0) {
        ++pc;
        continue;
      }
      calls.push_back({called->second + 1, flow.repeats - 1, pc + 1});
      pc = called->second + 1;
      continue;
    }
    if (flow.ret) {
      if (calls.empty()) {
        // M99 in the main program starts it again, endlessly, on the control.
        spdlog::warn(
            "{}:{}: M99 in the main program repeats it without end on the control; "
            "abbe follows one pass",
            file, line.number);
        break;
      }
      Frame& frame = calls.back();
      if (frame.remaining > 0) {
        --frame.remaining;
        pc = frame.body;
      } else {
        pc = frame.return_to;
        calls.pop_back();
      }
      continue;
    }
    ++pc;
  }
  if (!calls.empty() && pc >= lines.size())
    throw InputError(SourceLocation{file, lines.empty() ? 0 : lines.back().number, 0, "", ""},
                     "the file ends inside a subprogram (no M99)");
  interpreter.finish(counting_sink);
  return stats;
}

}  // namespace abbe::gcode::detail
