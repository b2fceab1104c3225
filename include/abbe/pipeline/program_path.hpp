#pragma once
// The front of abbe's one chain: an NC program read block by block
// (gcode::run_program: parser → interpreter) → motion stage → fragmenter →
// point sink. Every command that walks a program's toolpath (path, predict,
// simulate, the reports) goes through run_path, so they all see the same
// points.
#include <cstddef>
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
// Throws abbe::InputError on bad input (file, line, column).
PathRun run_path(std::istream& in, const std::string& file, const gcode::InterpreterConfig& config,
                 const PathOptions& options, const path::PointSink& sink);

// The point the error models evaluate at a path point (inline: once per point).
inline model::EvalPoint eval_point(const path::PathPoint& point) {
  model::EvalPoint p;
  p.p = point.p;
  p.tool_length = point.tool_length;
  p.dir = point.dir;
  p.time = point.time;
  return p;
}

}  // namespace abbe::pipeline
