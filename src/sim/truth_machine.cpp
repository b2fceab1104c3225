#include "abbe/sim/truth_machine.hpp"

#include <Eigen/Geometry>  // cross()
#include <cmath>

#include "abbe/io/units.hpp"

namespace abbe::sim {

namespace {

int sign_of(int v) { return (v > 0) - (v < 0); }
}  // namespace

Eigen::Vector3d rotation_minus_identity_times(const Eigen::Vector3d& theta,
                                              const Eigen::Vector3d& v) {
  // Rodrigues: R − I = a·[θ] + b·[θ]², a = sin|θ|/|θ|, b = (1 − cos|θ|)/|θ|².
  const double angle = theta.norm();
  double a = 1.0, b = 0.5;
  if (angle > 1e-4) {
    a = std::sin(angle) / angle;
    const double h = std::sin(0.5 * angle) / angle;
    b = 2.0 * h * h;
  } else {
    const double a2 = angle * angle;
    a = 1.0 - a2 / 6.0;
    b = 0.5 - a2 / 24.0;
  }
  const Eigen::Vector3d tv = theta.cross(v);
  return a * tv + b * theta.cross(tv);
}

Eigen::Vector3d TruthMachine::translation_um(int j, double s_j, int dir) const {
  const auto& c = axes[static_cast<std::size_t>(j)].components;
  return {c[0].value(s_j, dir), c[1].value(s_j, dir), c[2].value(s_j, dir)};
}

Eigen::Vector3d TruthMachine::rotation_urad(int j, double s_j, int dir) const {
  const auto& c = axes[static_cast<std::size_t>(j)].components;
  return {c[3].value(s_j, dir), c[4].value(s_j, dir), c[5].value(s_j, dir)};
}

Eigen::Vector3d TruthMachine::pivot(int j, const Eigen::Vector3d& s) const {
  Eigen::Vector3d c = axes[static_cast<std::size_t>(j)].pivot0;
  for (int i = 0; i < 3; ++i)
    if (chain.moves(j, i)) c[i] += s[i];
  return c;
}

Eigen::Vector3d TruthMachine::axis_displacement_mm(int j, const Eigen::Vector3d& s, int dir,
                                                   const Eigen::Vector3d& p) const {
  const Eigen::Vector3d t_mm = units::kMmPerUm * translation_um(j, s[j], dir);
  const Eigen::Vector3d theta = units::kRadPerUrad * rotation_urad(j, s[j], dir);
  return rotation_minus_identity_times(theta, p - pivot(j, s)) + t_mm;
}

Eigen::Vector3d TruthMachine::laser_linear_reading_um(int j, const Eigen::Vector3d& s, int dir,
                                                      const Eigen::Vector3d& m) const {
  return units::kUmPerMm * axis_displacement_mm(j, s, dir, m);
}

Eigen::Vector3d TruthMachine::geometric_deviation_um(const TipState& tip) const {
  const Eigen::Vector3d s = axis_positions(tip.p, tip.tool_length);
  // P' = E_a1(E_a2(E_a3(P))): the axis written next to the tool acts first.
  // The displacement is accumulated separately from P to keep its precision.
  Eigen::Vector3d d_mm = Eigen::Vector3d::Zero();
  for (int k = 2; k >= 0; --k) {
    const int j = chain.order()[static_cast<std::size_t>(k)];
    d_mm += axis_displacement_mm(j, s, tip.dir[static_cast<std::size_t>(j)], tip.p + d_mm);
  }
  Eigen::Vector3d d = units::kUmPerMm * d_mm;
  // Squareness (first order, µrad·mm in µm).
  const Eigen::Vector3d& p = tip.p;
  d.x() += units::kUmPerUradMm * (-squareness.ec0y * p.y() + squareness.eb0z * p.z());
  d.y() += units::kUmPerUradMm * (-squareness.ea0z * p.z());
  return d;
}

Eigen::Vector3d TruthMachine::effects_um(const TipState& tip) const {
  const Eigen::Vector3d s = axis_positions(tip.p, tip.tool_length);
  Eigen::Vector3d d = Eigen::Vector3d::Zero();
  for (const Effect& e : effects) {
    const int a = e.axis;
    const double sa = s[a];
    const int dir_a = sign_of(tip.dir[static_cast<std::size_t>(a)]);
    switch (e.kind) {
      case EffectKind::reversal:
        d[e.direction] += 0.5 * dir_a * e.magnitude;
        break;
      case EffectKind::scale:
        d[e.direction] += e.magnitude * sa / 1000.0;
        break;
      case EffectKind::thermal_drift: {
        const double f = drift_fraction(tip.time, e.tau_s, e.lag_s);
        d[e.direction] += (e.unit == "ppm" ? e.magnitude * sa / 1000.0 : e.magnitude) * f;
        break;
      }
      case EffectKind::cyclic:
        d[e.direction] += e.magnitude * std::sin(units::kTwoPi * sa / e.period_mm + e.phase_rad);
        break;
      case EffectKind::coupling: {
        auto normalised = [&](int i) {
          const AxisTruth& ax = axes[static_cast<std::size_t>(i)];
          const double mid = 0.5 * (ax.travel_min + ax.travel_max);
          const double half = 0.5 * (ax.travel_max - ax.travel_min);
          return half > 0.0 ? (s[i] - mid) / half : 0.0;
        };
        d[e.direction] += e.magnitude * normalised(a) * normalised(e.with_axis);
        break;
      }
      case EffectKind::arm_offset: {
        const Eigen::Vector3d delta = e.magnitude * Eigen::Vector3d::Unit(e.direction);
        d += units::kUmPerUradMm * rotation_urad(a, sa, dir_a).cross(delta);
        break;
      }
      case EffectKind::setup:
        if (!e.set.empty() && e.set != tip.set) break;
        if (e.unit == "um")
          d[a] += e.magnitude;
        else
          d += units::kUmPerUradMm * e.magnitude * Eigen::Vector3d::Unit(a).cross(tip.p - e.centre);
        break;
    }
  }
  return d;
}

Eigen::Vector3d TruthMachine::deviation_um(const TipState& tip) const {
  return geometric_deviation_um(tip) + effects_um(tip);
}

}  // namespace abbe::sim
