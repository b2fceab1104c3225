#pragma once
// LineSpan: a straight motion from p_start to p_end, parametrised by
// t ∈ [0, 1] proportional to length.
#include <Eigen/Core>

namespace abbe::path {

class LineSpan {
 public:
  LineSpan(const Eigen::Vector3d& p_start, const Eigen::Vector3d& p_end)
      : p_start_(p_start), p_end_(p_end) {}

  double length() const { return (p_end_ - p_start_).norm(); }
  // Point at fraction t of the length; t = 1 gives p_end bit-exactly.
  Eigen::Vector3d point(double t) const {
    if (t >= 1.0) return p_end_;
    return p_start_ + t * (p_end_ - p_start_);
  }
  // Velocity d point / d t (constant).
  Eigen::Vector3d velocity() const { return p_end_ - p_start_; }

 private:
  Eigen::Vector3d p_start_;
  Eigen::Vector3d p_end_;
};

}  // namespace abbe::path
