#pragma once
// MotionPath: the geometry of one Motion as a curve t ∈ [0, 1] → point (mm):
// a straight segment, or an arc/helix about its centre with the radius
// blended linearly from the start radius to the end radius and the
// normal-axis coordinate moving linearly (the interpreter's arc). Used to
// place compensation pieces and to measure distances to a nominal path.
#include <Eigen/Core>
#include <array>

#include "abbe/gcode/motion.hpp"

namespace abbe::compensate {

// Indices of the plane's (first, second, normal) axes: XY (0,1,2), XZ
// (2,0,1), YZ (1,2,0), so that positive angles turn counter-clockwise.
std::array<int, 3> plane_axes(gcode::Plane plane);

class MotionPath {
 public:
  explicit MotionPath(const gcode::Motion& motion);

  Eigen::Vector3d at(double t) const;
  double length() const { return length_; }
  bool is_arc() const { return arc_; }
  double sweep() const { return sweep_; }  // signed angle of an arc, rad
  // Shortest distance from q to the curve, mm.
  double distance(const Eigen::Vector3d& q) const;
  // Parameter of the point of the curve nearest to q.
  double closest(const Eigen::Vector3d& q) const;

 private:
  Eigen::Vector3d start_, end_, center_;
  std::array<int, 3> ax_{0, 1, 2};
  bool arc_ = false;
  double theta0_ = 0.0, sweep_ = 0.0, r0_ = 0.0, r1_ = 0.0, length_ = 0.0;
};

}  // namespace abbe::compensate
