#include "abbe/path/arc_span.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "abbe/io/units.hpp"

namespace abbe::path {

double arc_sweep(double theta_start, double theta_end, double chord, int rotation) {
  const bool ccw = rotation > 0;
  double sweep;
  if (chord < kFullCircleChord) {
    sweep = units::kTwoPi;
  } else {
    sweep = ccw ? theta_end - theta_start : theta_start - theta_end;  // in (-2π, 2π)
    // LinuxCNC's full-circle rule (CIRCLE_FUZZ): a sweep below 1e-6 rad is
    // a full turn more.
    if (sweep < kFullCircleSweep) sweep += units::kTwoPi;
  }
  const int turns = std::abs(rotation) - 1;
  sweep += units::kTwoPi * turns;
  return ccw ? sweep : -sweep;
}

ArcSpan::ArcSpan(const gcode::Motion& motion)
    : axes_(plane_axes(motion.plane)),
      p_start_(motion.start),
      p_end_(motion.end),
      center_(motion.center) {
  if (motion.rotation == 0)
    throw std::invalid_argument("arc motion with rotation 0 (line " + std::to_string(motion.line) +
                                ")");
  const int a = axes_[0];
  const int b = axes_[1];
  const double sa = p_start_[a] - center_[a];
  const double sb = p_start_[b] - center_[b];
  const double ea = p_end_[a] - center_[a];
  const double eb = p_end_[b] - center_[b];
  r0_ = std::hypot(sa, sb);
  r1_ = std::hypot(ea, eb);
  theta0_ = std::atan2(sb, sa);
  sweep_ = arc_sweep(theta0_, std::atan2(eb, ea), std::hypot(ea - sa, eb - sb), motion.rotation);
}

double ArcSpan::length() const {
  const int n = axes_[2];
  const double planar = 0.5 * (r0_ + r1_) * std::abs(sweep_);
  return std::hypot(planar, p_end_[n] - p_start_[n]);
}

double ArcSpan::length_bound() const {
  const int n = axes_[2];
  return std::hypot(std::max(r0_, r1_) * std::abs(sweep_), p_end_[n] - p_start_[n]);
}

Eigen::Vector3d ArcSpan::point(double t) const {
  if (t >= 1.0) return p_end_;
  if (t <= 0.0) return p_start_;
  const int a = axes_[0], b = axes_[1], n = axes_[2];
  const double theta = theta0_ + sweep_ * t;
  const double r = r0_ + (r1_ - r0_) * t;
  Eigen::Vector3d p;
  p[a] = center_[a] + r * std::cos(theta);
  p[b] = center_[b] + r * std::sin(theta);
  p[n] = p_start_[n] + (p_end_[n] - p_start_[n]) * t;
  return p;
}

Eigen::Vector3d ArcSpan::velocity(double t) const {
  const int a = axes_[0], b = axes_[1], n = axes_[2];
  const double theta = theta0_ + sweep_ * t;
  const double r = r0_ + (r1_ - r0_) * t;
  Eigen::Vector3d v;
  v[a] = -r * sweep_ * std::sin(theta);
  v[b] = r * sweep_ * std::cos(theta);
  v[n] = p_end_[n] - p_start_[n];
  return v;
}

void ArcSpan::sample(double t, Eigen::Vector3d& p, Eigen::Vector3d& v) const {
  const int a = axes_[0], b = axes_[1], n = axes_[2];
  const double theta = theta0_ + sweep_ * t;
  const double r = r0_ + (r1_ - r0_) * t;
  const double c = std::cos(theta), s = std::sin(theta);  // one sincos call
  v[a] = -r * sweep_ * s;
  v[b] = r * sweep_ * c;
  v[n] = p_end_[n] - p_start_[n];
  if (t >= 1.0) {
    p = p_end_;
    return;
  }
  p[a] = center_[a] + r * c;
  p[b] = center_[b] + r * s;
  p[n] = p_start_[n] + (p_end_[n] - p_start_[n]) * t;
}

}  // namespace abbe::path
