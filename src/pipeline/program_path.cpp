#include "abbe/pipeline/program_path.hpp"

#include <cmath>

namespace abbe::pipeline::detail {

gcode::InterpreterConfig path_config(const gcode::InterpreterConfig& config,
                                     const PathOptions& options) {
  gcode::InterpreterConfig c = config;
  c.dialect = options.dialect;
  return c;
}

std::array<bool, 3> held_axes(const gcode::Motion& m, double min_reversal_mm) {
  std::array<bool, 3> hold{false, false, false};
  for (Eigen::Index a = 0; a < 3; ++a)
    hold[static_cast<std::size_t>(a)] =
        m.kind != gcode::MotionKind::arc && std::abs(m.end[a] - m.start[a]) < min_reversal_mm;
  return hold;
}

}  // namespace abbe::pipeline::detail
