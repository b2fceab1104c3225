#pragma once
// ArcSpan: a circular arc or helix as the interpreter describes it
// (gcode::Motion with kind == arc), parametrised by t ∈ [0, 1] proportional to
// arc length.
//
// In plane coordinates (a, b, n) = gcode::plane_axes — XY: (x, y, z), XZ (G18): (z, x, y),
// YZ (G19): (y, z, x), so that a × b = n — the point at t is
//   θ(t) = θ0 + φ·t,  r(t) = r0 + (r1 − r0)·t,  n(t) = n0 + (n1 − n0)·t,
//   p = c + r(t)·(cos θ, sin θ) in (a, b),
// where φ is the signed sweep (> 0 counter-clockwise seen from +n), including
// the extra full turns. r0 and r1 are the start and end radii: an end point
// that is off the circle within the interpreter's tolerance is reached by
// letting the radius change linearly (as LinuxCNC does). A helix has constant
// speed in θ, so equal steps in t are equal steps in arc length (up to the
// tiny radius change).
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstddef>

#include "abbe/gcode/motion.hpp"

namespace abbe::path {

// Start and end of an arc closer than this in its plane (mm) make a full
// circle.
inline constexpr double kFullCircleChord = 1e-9;
// A first-turn sweep below this (rad) is a full circle, as in LinuxCNC
// (posemath's CIRCLE_FUZZ): the arc goes once round, not 0.1 µm.
inline constexpr double kFullCircleSweep = 1e-6;

// The signed sweep of an arc, rad (> 0 counter-clockwise seen from +n),
// from the angles of its start and end about the centre, the chord between
// them in the plane (mm) and gcode::Motion::rotation (sign: direction,
// magnitude: turns). The one rule of the fragmenter, the compensator and the
// verifier: a chord under kFullCircleChord is a full turn; otherwise the
// sweep of the first turn is in [kFullCircleSweep, 2π + kFullCircleSweep).
double arc_sweep(double theta_start, double theta_end, double chord, int rotation);

class ArcSpan {
 public:
  // Throws std::invalid_argument if motion.rotation == 0.
  explicit ArcSpan(const gcode::Motion& motion);

  // Helix length sqrt((r̄·φ)² + h²), r̄ the mean radius, h the normal travel.
  double length() const;
  // The same with the larger of the two radii: an upper bound of the true
  // length, used to choose the number of points so that no step exceeds the
  // limit even while the radius changes.
  double length_bound() const;
  // Point at fraction t of the arc length; t = 1 gives the motion's end point
  // bit-exactly, t = 0 its start point.
  Eigen::Vector3d point(double t) const;
  // Velocity d point / d t of the ideal circle through the point (the radius
  // change is left out so that a direction sign does not flip where the
  // tangential velocity of an axis vanishes).
  Eigen::Vector3d velocity(double t) const;
  // point(t) and velocity(t) together (one sine and cosine).
  void sample(double t, Eigen::Vector3d& p, Eigen::Vector3d& v) const;
  // Calls f(i, p, v) with p, v = sample(i / n) for i = 1 … n, in order (the
  // last p is the end point bit-exactly). The angle advances by rotating the
  // previous (cos, sin) pair, re-seeded from std::cos/std::sin every
  // kReseed points and at the end, so the points agree with sample() to
  // ~1e-14 relative.
  template <class F>
  void for_each_sample(std::size_t n, F&& f) const;

  double sweep() const { return sweep_; }  // signed, rad
  double start_radius() const { return r0_; }
  double end_radius() const { return r1_; }

 private:
  template <int a, int b, int k, class F>
  void for_each_sample_in(std::size_t n, F& f) const;

  std::array<int, 3> axes_;  // a, b, n
  Eigen::Vector3d p_start_;
  Eigen::Vector3d p_end_;
  Eigen::Vector3d center_;
  double r0_ = 0.0;
  double r1_ = 0.0;
  double theta0_ = 0.0;
  double sweep_ = 0.0;
};

template <class F>
void ArcSpan::for_each_sample(std::size_t n, F&& f) const {
  // The plane's axes as constants: the point and the velocity then stay in
  // registers (written through run-time indices, they went through memory,
  // and reading a vector just written a component at a time stalls).
  if (axes_ == std::array<int, 3>{0, 1, 2}) {
    for_each_sample_in<0, 1, 2>(n, f);
  } else if (axes_ == std::array<int, 3>{2, 0, 1}) {
    for_each_sample_in<2, 0, 1>(n, f);
  } else {
    for_each_sample_in<1, 2, 0>(n, f);
  }
}

template <int a, int b, int k, class F>
void ArcSpan::for_each_sample_in(std::size_t n, F& f) const {
  constexpr std::size_t kReseed = 32;
  const double dn = static_cast<double>(n);
  const double inv_n = 1.0 / dn;
  const double dtheta = sweep_ * inv_n;
  const double cd = std::cos(dtheta), sd = std::sin(dtheta);
  const double h = p_end_[k] - p_start_[k];
  double c = 0.0, s = 0.0;
  Eigen::Vector3d p, v;
  v[k] = h;
  for (std::size_t i = 1; i <= n; ++i) {
    const double t = static_cast<double>(i) * inv_n;  // i = n gives the exact end below
    if ((i - 1) % kReseed == 0 || i == n) {
      const double theta = theta0_ + sweep_ * t;
      c = std::cos(theta);
      s = std::sin(theta);
    } else {
      const double c_next = c * cd - s * sd;
      s = s * cd + c * sd;
      c = c_next;
    }
    const double r = r0_ + (r1_ - r0_) * t;
    v[a] = -r * sweep_ * s;
    v[b] = r * sweep_ * c;
    if (i == n) {
      p = p_end_;
    } else {
      p[a] = center_[a] + r * c;
      p[b] = center_[b] + r * s;
      p[k] = p_start_[k] + h * t;
    }
    f(i, static_cast<const Eigen::Vector3d&>(p), static_cast<const Eigen::Vector3d&>(v));
  }
}

}  // namespace abbe::path
