#include "abbe/compensate/motion_path.hpp"

#include <algorithm>
#include <cmath>

namespace abbe::compensate {

std::array<int, 3> plane_axes(gcode::Plane plane) {
  switch (plane) {
    case gcode::Plane::xz:
      return {2, 0, 1};
    case gcode::Plane::yz:
      return {1, 2, 0};
    default:
      return {0, 1, 2};
  }
}

MotionPath::MotionPath(const gcode::Motion& m)
    : start_(m.start), end_(m.end), center_(m.center), arc_(m.kind == gcode::MotionKind::arc) {
  if (!arc_) {
    length_ = (end_ - start_).norm();
    return;
  }
  ax_ = plane_axes(m.plane);
  const int a = ax_[0], b = ax_[1], n = ax_[2];
  const double us = start_[a] - center_[a], vs = start_[b] - center_[b];
  const double ue = end_[a] - center_[a], ve = end_[b] - center_[b];
  r0_ = std::hypot(us, vs);
  r1_ = std::hypot(ue, ve);
  theta0_ = std::atan2(vs, us);
  const double two_pi = 2.0 * M_PI;
  double d = std::atan2(ve, ue) - theta0_;
  const int turns = std::abs(m.rotation);
  if (m.rotation >= 0) {
    while (d <= 1e-12) d += two_pi;
    while (d > two_pi + 1e-12) d -= two_pi;
    d += two_pi * (turns - 1);
  } else {
    while (d >= -1e-12) d -= two_pi;
    while (d < -two_pi - 1e-12) d += two_pi;
    d -= two_pi * (turns - 1);
  }
  sweep_ = d;
  const double planar = std::abs(sweep_) * 0.5 * (r0_ + r1_);
  length_ = std::hypot(planar, end_[n] - start_[n]);
}

Eigen::Vector3d MotionPath::at(double t) const {
  if (!arc_) return start_ + t * (end_ - start_);
  if (t >= 1.0) return end_;
  if (t <= 0.0) return start_;
  const double th = theta0_ + t * sweep_;
  const double r = r0_ + t * (r1_ - r0_);
  Eigen::Vector3d p;
  p[ax_[0]] = center_[ax_[0]] + r * std::cos(th);
  p[ax_[1]] = center_[ax_[1]] + r * std::sin(th);
  p[ax_[2]] = start_[ax_[2]] + t * (end_[ax_[2]] - start_[ax_[2]]);
  return p;
}

double MotionPath::distance(const Eigen::Vector3d& q) const { return (at(closest(q)) - q).norm(); }

double MotionPath::closest(const Eigen::Vector3d& q) const {
  if (!arc_) {
    const Eigen::Vector3d d = end_ - start_;
    const double l2 = d.squaredNorm();
    return l2 > 0.0 ? std::clamp((q - start_).dot(d) / l2, 0.0, 1.0) : 0.0;
  }
  // Coarse search, then golden-section refinement around the best sample.
  const int n = std::max(16, static_cast<int>(std::ceil(std::abs(sweep_) * 8.0)));
  int best = 0;
  double best_d = (at(0.0) - q).norm();
  for (int i = 1; i <= n; ++i) {
    const double di = (at(static_cast<double>(i) / n) - q).norm();
    if (di < best_d) {
      best_d = di;
      best = i;
    }
  }
  double lo = std::max(0, best - 1) / static_cast<double>(n);
  double hi = std::min(n, best + 1) / static_cast<double>(n);
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
  double f1 = (at(x1) - q).norm(), f2 = (at(x2) - q).norm();
  for (int it = 0; it < 60; ++it) {
    if (f1 < f2) {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - g * (hi - lo);
      f1 = (at(x1) - q).norm();
    } else {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + g * (hi - lo);
      f2 = (at(x2) - q).norm();
    }
  }
  if (best_d <= std::min(f1, f2)) return static_cast<double>(best) / n;
  return f1 < f2 ? x1 : x2;
}

}  // namespace abbe::compensate
