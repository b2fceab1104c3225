#include "abbe/gcode/arc_geometry.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace abbe::gcode {

namespace {
constexpr double kMmPerInch = 25.4;
constexpr double kSqrt2 = 1.41421356237309504880;
}  // namespace

ArcTolerances arc_tolerances(bool inch) {
  ArcTolerances tol{};
  if (inch) {
    tol.radius_min = 0.00005;
    tol.spiral_abs = 2 * 0.001 * kSqrt2;
  } else {
    tol.radius_min = 0.00005 * kMmPerInch;
    tol.spiral_abs = 2 * 0.01 * kSqrt2;
  }
  tol.spiral_rel = 0.001;
  tol.spiral_cap = 100.0 * tol.spiral_abs;
  tol.unit = inch ? "in" : "mm";
  return tol;
}

ArcCentre arc_centre_ijk(const Eigen::Vector2d& start, const Eigen::Vector2d& end,
                         const Eigen::Vector2d& offset, bool absolute_centre,
                         const ArcTolerances& tol) {
  ArcCentre out;
  out.centre = absolute_centre ? offset : Eigen::Vector2d(start + offset);
  const double r1 = (start - out.centre).norm();
  const double r2 = (end - out.centre).norm();
  if (r1 < tol.radius_min || r2 < tol.radius_min) {
    out.error = fmt::format("zero-radius arc (radius to start {:.4f} {}, to end {:.4f} {})", r1,
                            tol.unit, r2, tol.unit);
    return out;
  }
  // A mismatch is tolerated while it is small in absolute OR in relative
  // terms, but never beyond the hard cap (LinuxCNC's rule).
  const double abs_err = std::abs(r1 - r2);
  const double rel_err = abs_err / std::max(r1, r2);
  if ((abs_err > tol.spiral_abs && rel_err > tol.spiral_rel) || abs_err > tol.spiral_cap) {
    out.error = fmt::format(
        "arc radius mismatch: radius to end differs from radius to start (r1={:.4f} {}, "
        "r2={:.4f} {}, abs_err={:.4g} {}, rel_err={:.4f}%)",
        r1, tol.unit, r2, tol.unit, abs_err, tol.unit, rel_err * 100.0);
  }
  return out;
}

ArcCentre arc_centre_r(const Eigen::Vector2d& start, const Eigen::Vector2d& end, double radius,
                       bool clockwise, const ArcTolerances& tol) {
  ArcCentre out;
  const Eigen::Vector2d chord = end - start;
  if (chord.norm() == 0.0) {
    out.error = "R-format arc with identical start and end point (zero chord)";
    return out;
  }
  const double abs_radius = std::abs(radius);
  if (abs_radius < tol.radius_min) {
    out.error = fmt::format("zero-radius arc (R {:.4f} {})", radius, tol.unit);
    return out;
  }
  const Eigen::Vector2d mid = 0.5 * (start + end);
  double half_length = 0.5 * chord.norm();
  if (half_length - abs_radius > tol.radius_min) {
    out.error = fmt::format(
        "impossible R arc: radius {:.4f} {} is too small to reach the end point (half chord "
        "{:.4f} {})",
        abs_radius, tol.unit, half_length, tol.unit);
    return out;
  }
  if (half_length / abs_radius > 1.0 - 1e-12) half_length = abs_radius;  // semicircle
  // The centre lies on the perpendicular bisector of the chord, to the right
  // of the chord for a clockwise arc of at most 180 degrees (and for a
  // counter-clockwise arc of more), to the left otherwise.
  const bool right = clockwise == (radius > 0);
  const double theta = std::atan2(chord.y(), chord.x()) + (right ? -M_PI_2 : M_PI_2);
  const double offset = abs_radius * std::cos(std::asin(half_length / abs_radius));
  out.centre = mid + offset * Eigen::Vector2d(std::cos(theta), std::sin(theta));
  return out;
}

}  // namespace abbe::gcode
