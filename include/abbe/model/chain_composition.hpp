#pragma once
// The error motions of the three axes composed along the kinematic chain,
// generic over the scalar: double for the htm model (small-angle rotations
// about the axis frame origins) and Dual2 for the dual model (rotations
// I + [θ]ε + ½[θ]²ε² about the measurement points).
//
// Axis j alone moves the tool relative to the workpiece by the rigid motion
//   E_j(p)_k = p_k + δ_{j,k} + [(R_j − I)(p − C_{j,k})]_k ,
// where C_{j,k} is the pivot of component k (the point where δ_{j,k} is
// known: a measurement point M_{j,k}(q), or the frame origin O_j(q) for
// htm). With one pivot per axis this is R_j(p − C) + C + δ; with several it
// is the same rigid motion, because the δ's at different points differ by
// exactly (R_j − I)(M_k − M_l). The tip under all errors is
//   P' = E_{a1}(E_{a2}(E_{a3}(P)))   (a1 a2 a3: the axes from w to t),
// i.e. the axis next to the tool acts first.
#include <Eigen/Core>
#include <array>

#include "abbe/model/dual2.hpp"

namespace abbe::model {

template <typename T>
using Vector3 = Eigen::Matrix<T, 3, 1>;
template <typename T>
using Matrix3 = Eigen::Matrix<T, 3, 3>;

template <typename T>
struct AxisMotion {
  Vector3<T> delta;        // mm
  Matrix3<T> r_minus_i;    // R − I
  Eigen::Matrix3d pivots;  // column k: pivot C_{j,k}, mm
};

// [θ]: the cross-product matrix, [θ]v = θ × v.
inline Eigen::Matrix3d skew(const Eigen::Vector3d& t) {
  Eigen::Matrix3d k;
  k << 0.0, -t.z(), t.y(), t.z(), 0.0, -t.x(), -t.y(), t.x(), 0.0;
  return k;
}

// The error terms as scalars of each kind: plain numbers for double,
// ε-coefficients for Dual2.
template <typename T>
struct ErrorScalar;

template <>
struct ErrorScalar<double> {
  static double linear(double x) { return x; }
  // Small-angle rotation of the conventional HTM: R − I = [θ].
  static void rotation_minus_identity(const Eigen::Vector3d& theta_rad, Eigen::Matrix3d& r) {
    r = skew(theta_rad);
  }
};

template <>
struct ErrorScalar<Dual2> {
  static Dual2 linear(double x) { return {0.0, x, 0.0}; }
  // exp([θ]ε) − I = [θ]ε + ½[θ]²ε² (ε³ = 0), with [θ]² = θθᵀ − |θ|²I.
  static void rotation_minus_identity(const Eigen::Vector3d& t, Matrix3<Dual2>& r) {
    const double n2 = t.squaredNorm();
    r(0, 0) = Dual2(0.0, 0.0, 0.5 * (t.x() * t.x() - n2));
    r(1, 1) = Dual2(0.0, 0.0, 0.5 * (t.y() * t.y() - n2));
    r(2, 2) = Dual2(0.0, 0.0, 0.5 * (t.z() * t.z() - n2));
    const double xy = 0.5 * t.x() * t.y(), xz = 0.5 * t.x() * t.z(), yz = 0.5 * t.y() * t.z();
    r(0, 1) = Dual2(0.0, -t.z(), xy);
    r(1, 0) = Dual2(0.0, t.z(), xy);
    r(0, 2) = Dual2(0.0, t.y(), xz);
    r(2, 0) = Dual2(0.0, -t.y(), xz);
    r(1, 2) = Dual2(0.0, -t.x(), yz);
    r(2, 1) = Dual2(0.0, t.x(), yz);
  }
};

// Displacement d' of the tip after one more axis: E_j(P + d) − P.
template <typename T>
inline void apply_axis_motion(const Eigen::Vector3d& p_tip, const AxisMotion<T>& m, Vector3<T>& d) {
  Vector3<T> out;
  for (int k = 0; k < 3; ++k) {
    T sum = d[k] + m.delta[k];
    for (int l = 0; l < 3; ++l) sum += m.r_minus_i(k, l) * (d[l] + (p_tip[l] - m.pivots(l, k)));
    out[k] = sum;
  }
  d = out;
}

// P' − P for the axes in chain order: motion_of(c, m) fills the error motion
// of the c-th axis from the workpiece (c = 2 next to the tool acts first).
// One workspace motion is reused (no per-axis temporaries).
template <typename T, typename MotionOf>
Vector3<T> compose_chain(const Eigen::Vector3d& p_tip, MotionOf&& motion_of) {
  Vector3<T> d = Vector3<T>::Constant(T(0.0));
  AxisMotion<T> m;
  for (int c = 2; c >= 0; --c) {
    motion_of(c, m);
    apply_axis_motion(p_tip, m, d);
  }
  return d;
}

}  // namespace abbe::model
