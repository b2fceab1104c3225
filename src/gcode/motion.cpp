#include "abbe/gcode/motion.hpp"

namespace abbe::gcode {

const char* to_string(MotionKind kind) {
  switch (kind) {
    case MotionKind::rapid:
      return "rapid";
    case MotionKind::linear:
      return "linear";
    case MotionKind::arc:
      return "arc";
    case MotionKind::dwell:
      return "dwell";
  }
  return "unknown";
}

}  // namespace abbe::gcode
