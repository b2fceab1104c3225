#pragma once
// PathPoint: one sample of the fragmented toolpath (what `abbe path` writes
// and what the error models evaluate).
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>

#include "abbe/gcode/motion.hpp"

namespace abbe::path {

struct PathPoint {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();  // tool tip, machine coordinates, mm
  double tool_length = 0.0;                     // active L, mm (s = p + L·e_z)
  std::size_t line = 0;                         // source line of the motion
  gcode::MotionKind kind = gcode::MotionKind::rapid;
  double feed = 0.0;  // mm/min (0 for rapids)
  double time = 0.0;  // estimated time since program start, s
  // Sign of the last motion of each axis before this point was reached (−1, 0, +1).
  std::array<std::int8_t, 3> dir{0, 0, 0};
};

}  // namespace abbe::path
