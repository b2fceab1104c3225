#pragma once
// Arc geometry of G2/G3 in the active plane, with LinuxCNC's (rs274ngc)
// rules and tolerances. Coordinates are the plane's (first, second) axes in
// the program frame, in program units: XY -> (X, Y), XZ (G18) -> (Z, X), YZ (G19) -> (Y, Z).
#include <Eigen/Core>
#include <optional>
#include <string>

namespace abbe::gcode {

// Tolerances, in program units.
struct ArcTolerances {
  double radius_min;          // radii below this are zero (and the R-format reach slack)
  double spiral_abs;          // |r_start - r_end| allowed without the relative test
  double spiral_rel = 0.001;  // relative to max(r_start, r_end)
  double spiral_cap;          // |r_start - r_end| never allowed beyond this (100 x spiral_abs)
  const char* unit = "mm";    // for messages
};

// mm programs: spiral 0.028284 mm, radius 0.00127 mm; inch programs:
// spiral 0.0028284 in, radius 0.00005 in.
ArcTolerances arc_tolerances(bool inch);

struct ArcCentre {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  std::string error;  // non-empty: the arc is refused, this says why
};

// Centre from I/J/K: `offset` is the centre relative to `start` (incremental
// arc distance mode) or the absolute centre. Checks the radius mismatch.
ArcCentre arc_centre_ijk(const Eigen::Vector2d& start, const Eigen::Vector2d& end,
                         const Eigen::Vector2d& offset, bool absolute_centre,
                         const ArcTolerances& tol);

// Centre from R: `clockwise` is G2; a negative radius selects the arc of more
// than 180 degrees.
ArcCentre arc_centre_r(const Eigen::Vector2d& start, const Eigen::Vector2d& end, double radius,
                       bool clockwise, const ArcTolerances& tol);

}  // namespace abbe::gcode
