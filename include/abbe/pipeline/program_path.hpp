#pragma once
// The front of abbe's one chain: an NC program read block by block
// (gcode::run_program: parser → interpreter) → motion stage → fragmenter →
// point sink. Every command that walks a program's toolpath (path, predict,
// simulate, the reports) goes through run_path, so they all see the same
// points.
#include <array>
#include <cstddef>
#include <cstdint>
#include <istream>
#include <string>

#include "abbe/gcode/interpreter.hpp"
#include "abbe/gcode/program.hpp"
#include "abbe/model/error_model.hpp"
#include "abbe/path/fragmenter.hpp"
#include "abbe/path/path_point.hpp"

namespace abbe::pipeline {

struct PathOptions {
  path::FragmentOptions fragment;
  // Direction stage: an axis that moves less than this within a straight
  // motion keeps the direction sign it had (the micro-motions a compensation
  // adds to an axis at rest are no reversals, as in `abbe verify`). 0: every
  // motion counts (as `abbe predict`).
  double min_reversal_mm = 0.0;
  // How the program is written (LinuxCNC or Fanuc/Haas); replaces the
  // dialect of the interpreter configuration handed to run_path.
  gcode::DialectOptions dialect;
};

struct PathRun {
  gcode::ProgramStats program;  // lines read, motions executed
  std::size_t points = 0;       // points handed to the sink
  double time_s = 0.0;          // estimated duration
};

// Streams the program at `in` (named `file` in errors) through the chain.
// `sink`: callable as sink(const path::PathPoint&); a template so that a
// lambda is inlined into the fragmenter's point loops (a path::PointSink
// works too). Throws abbe::InputError on bad input (file, line, column).
template <class Sink>
PathRun run_path(std::istream& in, const std::string& file, const gcode::InterpreterConfig& config,
                 const PathOptions& options, Sink&& sink);

namespace detail {
// `config` with the dialect of `options`.
gcode::InterpreterConfig path_config(const gcode::InterpreterConfig& config,
                                     const PathOptions& options);
// Direction stage: per motion, which axes keep their previous sign (a
// straight motion shorter than options.min_reversal_mm on that axis).
std::array<bool, 3> held_axes(const gcode::Motion& m, double min_reversal_mm);
}  // namespace detail

// The point the error models evaluate at a path point (inline: once per point).
inline model::EvalPoint eval_point(const path::PathPoint& point) {
  model::EvalPoint p;
  p.p = point.p;
  p.tool_length = point.tool_length;
  p.dir = point.dir;
  p.time = point.time;
  return p;
}

template <class Sink>
PathRun run_path(std::istream& in, const std::string& file, const gcode::InterpreterConfig& config,
                 const PathOptions& options, Sink&& sink) {
  path::Fragmenter fragmenter(options.fragment);
  PathRun run;
  if (!(options.min_reversal_mm > 0.0)) {
    run.program = gcode::run_program(in, file, detail::path_config(config, options),
                                     [&](const gcode::Motion& m) { fragmenter.add(m, sink); });
  } else {
    std::array<bool, 3> hold{false, false, false};
    std::array<std::int8_t, 3> dir{0, 0, 0};
    path::PathPoint held;
    const auto holding = [&](const path::PathPoint& p) {
      held = p;
      for (std::size_t a = 0; a < 3; ++a)
        if (!hold[a]) dir[a] = p.dir[a];
      held.dir = dir;
      sink(static_cast<const path::PathPoint&>(held));
    };
    run.program = gcode::run_program(in, file, detail::path_config(config, options),
                                     [&](const gcode::Motion& m) {
                                       hold = detail::held_axes(m, options.min_reversal_mm);
                                       fragmenter.add(m, holding);
                                     });
  }
  run.points = fragmenter.points();
  run.time_s = fragmenter.time();
  return run;
}

}  // namespace abbe::pipeline
