#pragma once
// AxisErrorTable: the six component errors of one axis (δ_X, δ_Y, δ_Z in µm,
// ε_A, ε_B, ε_C in µrad) as one piecewise-linear function of the axis
// position s_j, for one direction of motion. The component series are
// resampled onto the union of their breakpoints when the model is built —
// exact, because a piecewise-linear function stays piecewise linear on a
// finer grid — so a lookup finds one segment instead of six.
#include <Eigen/Core>
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

// The segment a lookup found last; points along a path move little, so the
// next lookup usually starts in the right segment.
struct TableCursor {
  std::size_t segment = 0;
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
  // Along a path the point usually stays in the segment found last: that
  // case is inline, everything else (another segment, clamping, empty or
  // one-knot tables) goes through eval_general.
  bool eval(double s, TableCursor& cursor, AxisErrors& out) const {
    const std::size_t i = cursor.segment;
    // s in [s_i, s_{i+1}): never a clamped end (below s_0 or at/after the last
    // knot), and at s_0 clamping gives the same value.
    if (i + 1 < s_.size() && s >= s_[i] && s < s_[i + 1]) {
      const Knot& k = knots_[i];
      const double t = s - s_[i];
      for (int d = 0; d < 3; ++d) {
        const auto c = static_cast<std::size_t>(d);
        out.delta_um[d] = k.value[c] + t * k.slope[c];
        out.theta_urad[d] = k.value[c + 3] + t * k.slope[c + 3];
      }
      return s >= lo_ && s <= hi_;
    }
    return eval_general(s, cursor, out);
  }

 private:
  struct Knot {
    std::array<double, 6> value;
    std::array<double, 6> slope;  // per mm, towards the next knot
  };
  std::size_t find_segment(double s, TableCursor& cursor) const;
  bool eval_general(double s, TableCursor& cursor, AxisErrors& out) const;

  std::vector<double> s_;
  std::vector<Knot> knots_;
  double lo_ = 0.0, hi_ = 0.0;
  bool extrapolate_ = false;
};

}  // namespace abbe::model
