#pragma once
// Canned drilling cycles (G73, G74, G81-G87, G89) expanded into the
// moves rs274ngc (LinuxCNC 2.9) makes. Coordinates are (aa, bb, cc) in the
// program frame, in program units (as rs274ngc computes them, so that the
// peck loop makes the same decisions): aa, bb the plane's first and second
// axes, cc the drilling axis (XY: X, Y, Z; XZ: Z, X, Y; YZ: Y, Z, X).
#include <Eigen/Core>
#include <functional>

namespace abbe::gcode {

struct CycleStep {
  enum class Kind { traverse, feed, dwell } kind = Kind::traverse;
  Eigen::Vector3d target = Eigen::Vector3d::Zero();  // (aa, bb, cc); for dwell: the position
  double seconds = 0.0;                              // dwell
};

struct CannedCycle {
  int code = 0;                                       // gcode_id(81), ...
  Eigen::Vector3d current = Eigen::Vector3d::Zero();  // position before the block
  double initial_level = 0.0;  // cc where the current series of cycles started (G98 level)
  Eigen::Vector2d hole = Eigen::Vector2d::Zero();       // position before the first increment
  Eigen::Vector2d increment = Eigen::Vector2d::Zero();  // per repeat (G91), zero in G90
  // Polar words in G91 (G17): per repeat, after `increment`, the hole's
  // radius about the program origin grows by this and its angle turns by
  // this (radians), as rs274ngc does (indeterminate at the origin: an error).
  double radius_increment = 0.0;
  double angle_increment = 0.0;
  double r = 0.0;            // R plane (absolute)
  double bottom = 0.0;       // hole bottom (absolute)
  bool retract_to_r = true;  // G99 (else G98: back to the initial level)
  int repeats = 1;           // L
  double dwell = 0.0;        // P, seconds (G82, G86, G89; G74/G84: 0 when not given)
  double peck = 0.0;         // Q (G73, G83), > 0
  // G87 (back boring, XY plane): the shift (I, J) the tool moves off the
  // hole's axis to pass through the bore, and the level K it bores up to
  // from the bottom (absolute).
  Eigen::Vector2d shift = Eigen::Vector2d::Zero();
  double back_bore_level = 0.0;
  // G73/G83: how far above the previous depth the tool returns (0.010 in;
  // rs274ngc: 0.010 in inch programs, 0.010 * 25.4 in mm programs).
  double peck_clearance = 0.254;
};

// Emits every step in order; returns the final position (aa, bb, clear level).
Eigen::Vector3d expand_canned_cycle(const CannedCycle& cycle,
                                    const std::function<void(const CycleStep&)>& emit);

}  // namespace abbe::gcode
