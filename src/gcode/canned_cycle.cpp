#include "abbe/gcode/canned_cycle.hpp"

#include <cmath>

#include "abbe/gcode/modal_groups.hpp"

namespace abbe::gcode {

Eigen::Vector3d expand_canned_cycle(const CannedCycle& c,
                                    const std::function<void(const CycleStep&)>& emit) {
  using Kind = CycleStep::Kind;
  auto move = [&](Kind kind, double aa, double bb, double cc) {
    emit(CycleStep{kind, Eigen::Vector3d(aa, bb, cc), 0.0});
  };
  double old_cc = c.initial_level;
  double current_cc = c.current.z();
  // Below the R plane: first straight up to it, where we stand.
  if (old_cc < c.r) {
    move(Kind::traverse, c.current.x(), c.current.y(), c.r);
    old_cc = c.r;
    current_cc = c.r;
  }
  const double clear = c.retract_to_r ? c.r : old_cc;
  double aa = c.hole.x();
  double bb = c.hole.y();
  for (int repeat = 0; repeat < c.repeats; ++repeat) {
    aa += c.increment.x();
    bb += c.increment.y();
    if (c.radius_increment != 0.0 && !(aa == 0.0 && bb == 0.0)) {
      const double theta = std::atan2(bb, aa);
      const double radius = std::hypot(bb, aa) + c.radius_increment;
      aa = radius * std::cos(theta);
      bb = radius * std::sin(theta);
    }
    if (c.angle_increment != 0.0 && !(aa == 0.0 && bb == 0.0)) {
      const double theta = std::atan2(bb, aa) + c.angle_increment;
      const double radius = std::hypot(bb, aa);
      aa = radius * std::cos(theta);
      bb = radius * std::sin(theta);
    }
    // Position over the hole: the first time at the current height (when it
    // is above R), afterwards at the clearance height; then down to R.
    if (repeat == 0 && current_cc > c.r) {
      move(Kind::traverse, aa, bb, current_cc);
      move(Kind::traverse, aa, bb, c.r);
    } else {
      move(Kind::traverse, aa, bb, clear);
      if (clear > c.r) move(Kind::traverse, aa, bb, c.r);
    }
    switch (c.code) {
      case gcode_id(81):
        move(Kind::feed, aa, bb, c.bottom);
        move(Kind::traverse, aa, bb, clear);
        break;
      case gcode_id(82):
        move(Kind::feed, aa, bb, c.bottom);
        emit(CycleStep{Kind::dwell, Eigen::Vector3d(aa, bb, c.bottom), c.dwell});
        move(Kind::traverse, aa, bb, clear);
        break;
      case gcode_id(85):
        move(Kind::feed, aa, bb, c.bottom);
        move(Kind::feed, aa, bb, c.r);
        move(Kind::traverse, aa, bb, clear);  // also when clear == R (rs274ngc does)
        break;
      case gcode_id(74):
      case gcode_id(84):
        // Tapping (rs274ngc): feed in, reverse the spindle, dwell P (0 when
        // not given), feed out to the clearance level, spindle forward.
        move(Kind::feed, aa, bb, c.bottom);
        emit(CycleStep{Kind::dwell, Eigen::Vector3d(aa, bb, c.bottom), c.dwell});
        move(Kind::feed, aa, bb, clear);
        break;
      case gcode_id(86):
        // Boring: feed in, dwell P, stop the spindle, rapid out, restart.
        move(Kind::feed, aa, bb, c.bottom);
        emit(CycleStep{Kind::dwell, Eigen::Vector3d(aa, bb, c.bottom), c.dwell});
        move(Kind::traverse, aa, bb, clear);
        break;
      case gcode_id(87): {
        // Back boring (rs274ngc): off the axis by the shift at R, spindle
        // stopped and oriented, down through the hole to the bottom, back on
        // the axis, spindle on, feed up to K and back down, stop and orient,
        // off the axis again and out to the clearance level, then over the hole.
        const double sa = aa + c.shift.x();
        const double sb = bb + c.shift.y();
        move(Kind::traverse, sa, sb, c.r);
        move(Kind::traverse, sa, sb, c.bottom);
        move(Kind::traverse, aa, bb, c.bottom);
        move(Kind::feed, aa, bb, c.back_bore_level);
        move(Kind::feed, aa, bb, c.bottom);
        move(Kind::traverse, sa, sb, c.bottom);
        move(Kind::traverse, sa, sb, clear);
        move(Kind::traverse, aa, bb, clear);
        break;
      }
      case gcode_id(89):
        move(Kind::feed, aa, bb, c.bottom);
        emit(CycleStep{Kind::dwell, Eigen::Vector3d(aa, bb, c.bottom), c.dwell});
        move(Kind::feed, aa, bb, clear);
        break;
      case gcode_id(73):
      case gcode_id(83): {
        // Peck: feed one Q deeper each time; G83 rapids out to the R plane
        // (not to the G98 level) and back down to just above the previous
        // depth, G73 only backs off by the peck clearance.
        for (double depth = c.r - c.peck; depth > c.bottom; depth -= c.peck) {
          move(Kind::feed, aa, bb, depth);
          if (c.code == gcode_id(83)) move(Kind::traverse, aa, bb, c.r);
          move(Kind::traverse, aa, bb, depth + c.peck_clearance);
        }
        move(Kind::feed, aa, bb, c.bottom);
        move(Kind::traverse, aa, bb, clear);
        break;
      }
      default:
        break;
    }
  }
  return Eigen::Vector3d(aa, bb, clear);
}

}  // namespace abbe::gcode
