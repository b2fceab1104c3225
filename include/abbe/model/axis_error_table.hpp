#pragma once
// AxisErrorTable: the six component errors of one axis (δ_X, δ_Y, δ_Z in µm,
// ε_A, ε_B, ε_C in µrad) as one piecewise-linear function of the axis
// position s_j, for one direction of motion. The component series are
// resampled onto the union of their breakpoints when the model is built —
// exact, because a piecewise-linear function stays piecewise linear on a
// finer grid — so a lookup finds one segment instead of six.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "abbe/machine/machine.hpp"

namespace abbe::model {

struct AxisErrors {
  Eigen::Vector3d delta_um = Eigen::Vector3d::Zero();    // EX·, EY·, EZ·
  Eigen::Vector3d theta_urad = Eigen::Vector3d::Zero();  // EA·, EB·, EC·
};

class AxisErrorTable {
 public:
  AxisErrorTable() = default;  // no data: every error is zero

  // The series of `axis` for motion direction `dir` (+1 fwd, −1 rev, 0 the
  // mean of fwd and rev); mean-only components serve every direction.
  static AxisErrorTable build(const machine::ComponentTable& table, machine::Axis axis, int dir,
                              machine::OutOfRangePolicy policy);

  bool empty() const { return knots_.empty(); }
  // The range where every component of this axis is measured, mm.
  double lo() const { return lo_; }
  double hi() const { return hi_; }
  const std::vector<double>& breakpoints() const { return s_; }

  // Values at s. Returns false when s lies outside [lo, hi] (the caller
  // counts it; clamp/extrapolate follow the policy the table was built with).
  // No search and no state: the segment is guessed from the first knot
  // spacing (exact on the campaign's evenly spaced targets, a shorter last
  // segment included) and corrected by stepping (segment()).
  bool eval(double s, AxisErrors& out) const {
    if (knots_.empty()) {
      out.delta_um.setZero();
      out.theta_urad.setZero();
      return true;
    }
    // Clamping evaluates the end segments at their end knots (the bounds are
    // infinite when the table extrapolates).
    const double x = std::min(std::max(s, clamp_lo_), clamp_hi_);
    const std::size_t i = segment(x);
    at(knots_[i], x - s_[i], out);
    return s >= lo_ && s <= hi_;
  }

 private:
  struct Knot {
    std::array<double, 6> value;
    std::array<double, 6> slope;  // per mm, towards the next knot
  };
  // The six values at distance t past knot k (computed into a local first:
  // the compiler then packs them two by two).
  static void at(const Knot& k, double t, AxisErrors& out) {
    double r[6];
    for (std::size_t c = 0; c < 6; ++c) r[c] = k.value[c] + t * k.slope[c];
    out.delta_um = Eigen::Vector3d(r[0], r[1], r[2]);
    out.theta_urad = Eigen::Vector3d(r[3], r[4], r[5]);
  }
  // The segment i ∈ [0, last_] with s_i ≤ x < s_{i+1} (the first or last one
  // outside the knots; NaN gives 0).
  std::size_t segment(double x) const {
    double guess = (x - s0_) * inv_step_;
    guess = guess > 0.0 ? guess : 0.0;  // also NaN
    guess = guess < last_d_ ? guess : last_d_;
    const auto i = static_cast<std::size_t>(static_cast<int>(guess));
    if (x < s_[i] && i > 0) return step_down(x, i);
    if (i < last_ && x >= s_[i + 1]) return step_up(x, i);
    return i;
  }
  std::size_t step_down(double x, std::size_t i) const;
  std::size_t step_up(double x, std::size_t i) const;

  std::vector<double> s_;
  std::vector<Knot> knots_;
  double lo_ = 0.0, hi_ = 0.0;
  double s0_ = 0.0;                         // first knot
  double inv_step_ = 0.0;                   // 1 / (s_1 − s_0); 0 with one knot
  std::size_t last_ = 0;                    // index of the last segment (0 with one knot)
  double last_d_ = 0.0;                     // the same as a double
  double clamp_lo_ = 0.0, clamp_hi_ = 0.0;  // the knots' range, or ±∞ to extrapolate
  bool extrapolate_ = false;
};

}  // namespace abbe::model
