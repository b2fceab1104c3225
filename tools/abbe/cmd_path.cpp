// abbe path: parse → interpret → fragment → write, block by block.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "abbe/gcode/program.hpp"
#include "abbe/io/atomic_file.hpp"
#include "abbe/io/input_error.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/path/fragmenter.hpp"
#include "abbe/pipeline/interpreter_setup.hpp"
#include "abbe/pipeline/path_writer.hpp"
#include "abbe/pipeline/program_path.hpp"
#include "command.hpp"
#include "dialect_option.hpp"
#include "input_stream.hpp"
#include "interpreter_options.hpp"
#include "output_options.hpp"
#include "progress.hpp"
#include "setup_options.hpp"

namespace abbe::cli {
namespace {

struct PathOptions {
  std::string program;
  std::string output = "-";
  std::string format = "csv";
  double step = 5.0;
  double rapid_rate = 10000.0;
  SetupOptions setup;
  std::string machine;
  bool count_only = false;
  gcode::DialectOptions dialect;
};

gcode::InterpreterConfig make_config(const PathOptions& o) {
  gcode::InterpreterConfig config;
  if (!o.machine.empty()) {
    config = pipeline::interpreter_config(machine::Machine::load(o.machine));
  }
  // The tool-tip path does not depend on the length of a G43 tool: a tool
  // without one in the table is accepted (one warning, tool_length unknown).
  config.allow_unknown_tool_length = true;
  apply_setup_options(o.setup, config);
  return config;
}

int run_path(const PathOptions& o, const GlobalOptions& g) {
  const gcode::InterpreterConfig config = make_config(o);
  const pipeline::PathFormat format = pipeline::parse_path_format(o.format);

  InputStream input(o.program, "NC program");
  std::istream& in = input.stream();
  const bool from_stdin = input.from_stdin();

  pipeline::PathOptions path_options;
  path_options.fragment.step = o.step;
  path_options.fragment.rapid_rate = o.rapid_rate;
  path_options.dialect = o.dialect;
  // Progress on a terminal: bytes of the program read (points from stdin).
  Progress progress("path", from_stdin ? 0 : Progress::file_size(o.program), !g.quiet,
                    from_stdin ? "points" : "bytes");
  std::size_t seen = 0;
  auto tick = [&] {
    if (!progress.active() || (++seen & 4095) != 0) return;
    if (from_stdin) return progress.update(seen);
    const auto pos = input.position();
    if (pos >= 0) progress.update(static_cast<std::uint64_t>(pos));
  };

  if (o.count_only) {
    // Fragments everything but writes only a summary (benchmarks, checks).
    const auto run = pipeline::run_path(in, o.program, config, path_options,
                                        [&](const path::PathPoint&) { tick(); });
    progress.finish();
    fmt::print("lines={} motions={} points={} time_s={:.3f}\n", run.program.lines,
               run.program.motions, run.points, run.time_s);
    return kOk;
  }

  io::AtomicOutputFile out(o.output);
  pipeline::PathWriter writer(format,
                              [&](const char* data, std::size_t size) { out.write(data, size); });
  const auto run =
      pipeline::run_path(in, o.program, config, path_options, [&](const path::PathPoint& p) {
        writer.write(p);
        tick();
      });
  progress.finish();
  writer.finish();
  out.commit();
  spdlog::debug("{}: {} lines, {} motions, {} points, {:.1f} s estimated", o.program,
                run.program.lines, run.program.motions, writer.points(), run.time_s);
  return kOk;
}

const CommandRegistrar registrar(
    "path",
    "Fragment an NC program into points (at most --step apart) and write them as CSV or JSON", 20,
    [](CLI::App& sub, const GlobalOptions& g) -> CommandAction {
      auto o = std::make_shared<PathOptions>();
      const GlobalOptions* gp = &g;
      sub.footer(
          "Example: abbe path nc-samples/thesis-toolpath-1.ngc "
          "--machine machines/sample/machine.yaml -o path.csv");
      sub.add_option("program", o->program, "NC program (RS274/LinuxCNC G-code), - for stdin")
          ->required();
      add_output_option(sub, o->output, "Output file")->capture_default_str();
      add_format_option(sub, o->format, {"csv", "json"});
      sub.add_option("--step", o->step, "Largest distance between points, mm")
          ->check(CLI::PositiveNumber)
          ->capture_default_str();
      sub.add_option("--rapid-rate", o->rapid_rate,
                     "Rate of rapid (G0) motions for the time estimate, mm/min")
          ->check(CLI::PositiveNumber)
          ->capture_default_str();
      add_setup_options(sub, o->setup);
      sub.add_option("--machine", o->machine,
                     "Machine file (YAML): tool length, tool table and work offsets");
      add_dialect_options(sub, o->dialect);
      sub.add_flag("--count,--null", o->count_only,
                   "Fragment but write only a one-line summary to stdout (no points)");
      return [o, gp] { return run_path(*o, *gp); };
    });

}  // namespace
}  // namespace abbe::cli
