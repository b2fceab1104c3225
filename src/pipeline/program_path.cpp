#include "abbe/pipeline/program_path.hpp"

#include <array>
#include <cmath>

namespace abbe::pipeline {

PathRun run_path(std::istream& in, const std::string& file,
                 const gcode::InterpreterConfig& machine_config, const PathOptions& options,
                 const path::PointSink& sink) {
  gcode::InterpreterConfig config = machine_config;
  config.dialect = options.dialect;
  path::FragmentOptions fragment = options.fragment;
  path::Fragmenter fragmenter(fragment);
  PathRun run;
  if (!(options.min_reversal_mm > 0.0)) {
    run.program = gcode::run_program(in, file, config,
                                     [&](const gcode::Motion& m) { fragmenter.add(m, sink); });
  } else {
    // Direction stage: per motion, which axes hold their previous sign.
    std::array<bool, 3> hold{false, false, false};
    std::array<std::int8_t, 3> dir{0, 0, 0};
    path::PathPoint held;
    const path::PointSink holding = [&](const path::PathPoint& p) {
      held = p;
      for (std::size_t a = 0; a < 3; ++a)
        if (!hold[a]) dir[a] = p.dir[a];
      held.dir = dir;
      sink(held);
    };
    run.program = gcode::run_program(in, file, config, [&](const gcode::Motion& m) {
      for (Eigen::Index a = 0; a < 3; ++a)
        hold[static_cast<std::size_t>(a)] =
            m.kind != gcode::MotionKind::arc &&
            std::abs(m.end[a] - m.start[a]) < options.min_reversal_mm;
      fragmenter.add(m, holding);
    });
  }
  run.points = fragmenter.points();
  run.time_s = fragmenter.time();
  return run;
}

}  // namespace abbe::pipeline
