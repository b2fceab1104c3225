#include "abbe/compensate/motion_path.hpp"

#include <algorithm>
#include <cmath>

#include "abbe/path/arc_span.hpp"

namespace abbe::compensate {

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
  r0_ = std::sqrt(us * us + vs * vs);  // no overflow at machine sizes: no hypot
  r1_ = std::sqrt(ue * ue + ve * ve);
  theta0_ = std::atan2(vs, us);
  // The fragmenter's rule for full circles and turns (path::arc_sweep).
  sweep_ = path::arc_sweep(theta0_, std::atan2(ve, ue), std::hypot(ue - us, ve - vs), m.rotation);
  const double planar = std::abs(sweep_) * 0.5 * (r0_ + r1_);
  const double h = end_[n] - start_[n];
  length_ = std::sqrt(planar * planar + h * h);
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

std::int8_t MotionPath::in_plane_direction(int k, double t) const {
  // Tangent of the ideal circle: (−sin θ, cos θ)·sweep.
  auto component = [&](double th) { return (k == 0 ? -std::sin(th) : std::cos(th)) * sweep_; };
  const double th = theta0_ + t * sweep_;
  double v = component(th);
  if (std::abs(v) <= 1e-9 * std::abs(sweep_)) v = component(th - 1e-6 * sweep_);
  return v > 0.0 ? 1 : -1;
}

double MotionPath::near_lo(double near) const {
  return length_ > 0.0 ? std::min(0.5, near / length_) : 0.5;
}

double MotionPath::distance_near(const Eigen::Vector3d& q) const {
  if (!arc_ || std::abs(sweep_) > units::kTwoPi) return distance(q);
  const int a = ax_[0], b = ax_[1], n = ax_[2];
  const double ua = q[a] - center_[a], ub = q[b] - center_[b];
  // Angle from the start in the direction of the sweep, in [0, 2π).
  double phi = std::atan2(ub, ua) - theta0_;
  if (sweep_ < 0.0) phi = -phi;
  phi = std::fmod(phi, units::kTwoPi);
  if (phi < 0.0) phi += units::kTwoPi;
  double t = phi / std::abs(sweep_);
  if (t > 1.0) return std::min((q - start_).norm(), (q - end_).norm());
  const double h = end_[n] - start_[n];
  if (h == 0.0) {
    const double r = r0_ + t * (r1_ - r0_);
    const double dr = std::sqrt(ua * ua + ub * ub) - r, dn = q[n] - start_[n];
    return std::sqrt(dr * dr + dn * dn);
  }
  // A helix: its tangent has a normal component; a Newton step on
  // (p(t) − q)·p'(t) from the angle's parameter (which is off by the
  // offset's share along the tangent only: one step leaves a second-order
  // error), then the distance there.
  const double dr = r1_ - r0_;
  auto offset = [&](double tt, double& c, double& s) {
    const double th = theta0_ + tt * sweep_;
    c = std::cos(th);
    s = std::sin(th);
    const double r = r0_ + tt * dr;
    return Eigen::Vector3d(center_[a] + r * c - q[a], center_[b] + r * s - q[b],
                           start_[n] + tt * h - q[n]);
  };
  double c = 0.0, s = 0.0;
  Eigen::Vector3d v = offset(t, c, s);  // (a, b, n) components
  const double r = r0_ + t * dr;
  const double da = dr * c - r * sweep_ * s, db = dr * s + r * sweep_ * c;
  const double g = v[0] * da + v[1] * db + v[2] * h;
  t = std::clamp(t - g / (da * da + db * db + h * h), 0.0, 1.0);
  v = offset(t, c, s);
  return v.norm();
}

double MotionPath::distance(const Eigen::Vector3d& q) const { return (at(closest(q)) - q).norm(); }

double MotionPath::closest(const Eigen::Vector3d& q) const {
  if (!arc_) {
    const Eigen::Vector3d d = end_ - start_;
    const double l2 = d.squaredNorm();
    return l2 > 0.0 ? std::clamp((q - start_).dot(d) / l2, 0.0, 1.0) : 0.0;
  }
  // The angle of q about the centre gives the parameter on each turn where
  // the planar distance is least; a few Newton steps on (p(t) − q)·p'(t)
  // take the radius blend and the helix travel into account. The ends are
  // candidates too.
  const int a = ax_[0], b = ax_[1], n = ax_[2];
  const double two_pi = units::kTwoPi;
  const double h = end_[n] - start_[n];
  const double dr = r1_ - r0_;
  const double alpha = std::atan2(q[b] - center_[b], q[a] - center_[a]);
  // t_k = (alpha + 2πk − θ0) / sweep for the k that fall in [0, 1].
  const double base = (alpha - theta0_) / sweep_;
  const double period = two_pi / std::abs(sweep_);  // t per turn
  double k_lo = std::ceil((0.0 - base) / period - 1.0);
  double k_hi = std::floor((1.0 - base) / period + 1.0);
  if (k_hi - k_lo > 4.0 && h != 0.0) {  // many turns: those nearest the helix height
    const double th = std::clamp((q[n] - start_[n]) / h, 0.0, 1.0);
    const double kc = std::round((th - base) / period);
    k_lo = std::max(k_lo, kc - 1.0);
    k_hi = std::min(k_hi, kc + 1.0);
  }
  auto dist2 = [&](double t) { return (at(t) - q).squaredNorm(); };
  double best_t = 0.0, best = dist2(0.0);
  const double d1 = dist2(1.0);
  if (d1 < best) {
    best = d1;
    best_t = 1.0;
  }
  for (double k = k_lo; k <= k_hi; k += 1.0) {
    double t = base + k * period;
    if (t < -0.5 * period || t > 1.0 + 0.5 * period) continue;
    t = std::clamp(t, 0.0, 1.0);
    for (int it = 0; it < 3; ++it) {
      const double th = theta0_ + t * sweep_;
      const double c = std::cos(th), s = std::sin(th);
      const double r = r0_ + t * dr;
      const double ua = center_[a] + r * c - q[a], ub = center_[b] + r * s - q[b];
      const double un = start_[n] + t * h - q[n];
      // p' and p'' in the (a, b, n) frame.
      const double da = dr * c - r * sweep_ * s, db = dr * s + r * sweep_ * c;
      const double dda = -2.0 * dr * sweep_ * s - r * sweep_ * sweep_ * c;
      const double ddb = 2.0 * dr * sweep_ * c - r * sweep_ * sweep_ * s;
      const double g = ua * da + ub * db + un * h;
      const double gp = da * da + db * db + h * h + ua * dda + ub * ddb;
      if (!(gp > 0.0)) break;
      const double next = std::clamp(t - g / gp, 0.0, 1.0);
      if (next == t) break;
      t = next;
    }
    const double dt = dist2(t);
    if (dt < best) {
      best = dt;
      best_t = t;
    }
  }
  return best_t;
}

}  // namespace abbe::compensate
