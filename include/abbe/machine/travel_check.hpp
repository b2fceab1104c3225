#pragma once
// TravelCheck: counts the points of a path whose axis positions
// s = P + L·e_z (tool tip P, tool length L) lie outside the machine's
// travel, per axis, and keeps the first lines where that happens. predict
// warns with it; compensate refuses such a program unless told otherwise
// (docs/compensation.md) — the error tables end at the travel, so a
// prediction there is a clamped guess and the machine cannot go there.
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "abbe/machine/machine.hpp"

namespace abbe::machine {

class TravelCheck {
 public:
  explicit TravelCheck(const std::array<Travel, 3>& travel);
  // Returns true if the point is inside on every axis. Inline (it runs once
  // per path point); a point outside is counted out of line.
  bool add(const Eigen::Vector3d& tip, double tool_length, std::size_t line) {
    ++points_;
    const double z = tip.z() + tool_length;
    if (inside(0, tip.x()) && inside(1, tip.y()) && inside(2, z)) return true;
    add_outside(Eigen::Vector3d(tip.x(), tip.y(), z), line);
    return false;
  }

  std::size_t points() const { return points_; }    // points checked
  std::size_t outside() const { return outside_; }  // points outside on any axis
  const std::array<std::size_t, 3>& outside_per_axis() const { return per_axis_; }
  const std::vector<std::size_t>& first_lines() const { return lines_; }  // first 5 distinct

  // "N of M points outside the travel (X a, Y b, Z c), first on lines l1, l2"; empty if none.
  std::string text() const;
  // "X 12.3 mm beyond [-990, 0]" for the axis position s of one point; empty if inside.
  std::string describe(const Eigen::Vector3d& tip, double tool_length) const;

 private:
  void add_outside(const Eigen::Vector3d& s, std::size_t line);
  // Whether axis position v lies within the travel of axis a (with the slack).
  bool inside(std::size_t a, double v) const { return v >= lo_[a] && v <= hi_[a]; }

  std::array<Travel, 3> travel_;
  std::array<double, 3> lo_{}, hi_{};  // the travel widened by the slack
  std::size_t points_ = 0, outside_ = 0;
  std::array<std::size_t, 3> per_axis_{0, 0, 0};
  std::vector<std::size_t> lines_;
};

}  // namespace abbe::machine
