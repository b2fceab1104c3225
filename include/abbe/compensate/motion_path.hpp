#pragma once
// MotionPath: the geometry of one Motion as a curve t ∈ [0, 1] → point (mm):
// a straight segment, or an arc/helix about its centre with the radius
// blended linearly from the start radius to the end radius and the
// normal-axis coordinate moving linearly (the interpreter's arc). Used to
// place compensation pieces and to measure distances to a nominal path.
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdint>

#include "abbe/gcode/motion.hpp"
#include "abbe/io/units.hpp"

namespace abbe::compensate {

// Distance from an end of an arc within which a reversal counts as at that
// end, and the least distance of a piece end from a reversal, mm.
constexpr double kNearReversal = 0.05;

class MotionPath {
 public:
  explicit MotionPath(const gcode::Motion& motion);

  Eigen::Vector3d at(double t) const;
  double length() const { return length_; }
  bool is_arc() const { return arc_; }
  double sweep() const { return sweep_; }  // signed angle of an arc, rad
  // Parameters in (t_lo, t_hi), ascending, where an in-plane axis of an arc
  // reverses (its tangent component vanishes: every quarter turn). Calls
  // f(t) for each; none for a line.
  template <class F>
  void for_each_reversal(double t_lo, double t_hi, F&& f) const;
  // Direction sign of plane axis k (0: first, 1: second) of an arc at t: the
  // tangent's; at a reversal itself the sign just before it.
  std::int8_t in_plane_direction(int k, double t) const;
  // `dir` with the in-plane axes of an arc set to in_plane_direction at t
  // (the normal axis, and every axis of a line, as given).
  std::array<std::int8_t, 3> directions(std::array<std::int8_t, 3> dir, double t) const {
    if (!arc_) return dir;
    for (std::size_t k = 0; k < 2; ++k)
      dir[static_cast<std::size_t>(ax_[k])] = in_plane_direction(static_cast<int>(k), t);
    return dir;
  }
  // Reversals closer than `near` (mm) to an end of an arc count as at that
  // end: the parameter range [lo, hi] inside which directions are taken
  // (t is clamped into it). Compensation and verification share this.
  double near_lo(double near) const;
  double near_hi(double near) const { return 1.0 - near_lo(near); }
  const std::array<int, 3>& axes() const { return ax_; }
  // Shortest distance from q to the curve, mm.
  double distance(const Eigen::Vector3d& q) const;
  // Parameter of the point of the curve nearest to q.
  double closest(const Eigen::Vector3d& q) const;
  // distance() for a point near the curve (within a small fraction of the
  // radius of an arc of at most one turn): a planar arc by the radial and
  // normal offsets at the point's own angle (one atan2, no iteration), a
  // helix with two Newton steps from there; else distance().
  double distance_near(const Eigen::Vector3d& q) const;

 private:
  Eigen::Vector3d start_, end_, center_;
  std::array<int, 3> ax_{0, 1, 2};
  bool arc_ = false;
  double theta0_ = 0.0, sweep_ = 0.0, r0_ = 0.0, r1_ = 0.0, length_ = 0.0;
};

template <class F>
void MotionPath::for_each_reversal(double t_lo, double t_hi, F&& f) const {
  if (!arc_ || sweep_ == 0.0) return;
  const double half_pi = 0.5 * units::kPi;
  const double a0 = theta0_ + t_lo * sweep_, a1 = theta0_ + t_hi * sweep_;
  if (sweep_ > 0.0) {
    for (double k = std::floor(a0 / half_pi) + 1.0; k * half_pi < a1; k += 1.0) {
      const double t = (k * half_pi - theta0_) / sweep_;
      if (t > t_lo && t < t_hi) f(t);
    }
  } else {
    for (double k = std::ceil(a0 / half_pi) - 1.0; k * half_pi > a1; k -= 1.0) {
      const double t = (k * half_pi - theta0_) / sweep_;
      if (t > t_lo && t < t_hi) f(t);
    }
  }
}

}  // namespace abbe::compensate
