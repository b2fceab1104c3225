#pragma once
// Bounds on what a motion may be: coordinates within ±kMaxCoordinateMm (no
// machine tool is a kilometre long; beyond, doubles lose the µm and point
// counts overflow), and MotionRefused, thrown by a stage downstream of the
// interpreter (the fragmenter: a motion needing too many points) for a
// motion it cannot take. The interpreter turns it into an InputError at the
// block's file, line and column; a stage that runs outside the interpreter's
// call does the same with its own block.
#include <stdexcept>
#include <string>

namespace abbe::gcode {

inline constexpr double kMaxCoordinateMm = 1e6;

class MotionRefused : public std::runtime_error {
 public:
  explicit MotionRefused(const std::string& why) : std::runtime_error(why) {}
};

}  // namespace abbe::gcode
