#include "abbe/path/fragmenter.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "abbe/gcode/motion_limits.hpp"
#include "abbe/io/units.hpp"
#include "abbe/path/arc_span.hpp"
#include "abbe/path/line_span.hpp"

namespace abbe::path {

namespace {
// More segments than this for one motion means a step far below any
// machine's resolution: refused rather than looping for hours.
constexpr double kMaxSegments = 1e9;
// A velocity component smaller than this fraction of the speed counts as
// zero (the axis keeps its previous direction sign).
constexpr double kDirectionTolerance = 1e-9;

std::int8_t sign(double v) { return v > 0.0 ? std::int8_t{1} : std::int8_t{-1}; }
}  // namespace

Fragmenter::Fragmenter(FragmentOptions options) : options_(options) {
  if (!(options_.step > 0.0) || !std::isfinite(options_.step))
    throw std::invalid_argument("fragment step must be a positive number of mm, got " +
                                std::to_string(options_.step));
  if (!(options_.rapid_rate > 0.0) || !std::isfinite(options_.rapid_rate))
    throw std::invalid_argument("rapid rate must be a positive number of mm/min, got " +
                                std::to_string(options_.rapid_rate));
}

std::size_t Fragmenter::segments(double length, const gcode::Motion& motion) const {
  const double q = length / options_.step;
  if (!(q <= kMaxSegments))
    throw gcode::MotionRefused(
        fmt::format("the {} motion of {:.6g} mm needs more than 1e9 points at step {} mm (a typo "
                    "in a coordinate? a larger --step takes it)",
                    gcode::to_string(motion.kind), length, options_.step));
  return std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(q)));
}

void Fragmenter::emit(PathPoint& point, const PointSink& sink) {
  point.dir = dir_;
  ++points_;
  sink(point);
}

void Fragmenter::add(const gcode::Motion& motion, const PointSink& sink) {
  if (motion.kind == gcode::MotionKind::dwell) {
    if (motion.dwell_seconds > 0.0) time_ += motion.dwell_seconds;
    return;
  }
  PathPoint point;
  point.tool_length = motion.tool_length;
  point.line = motion.line;
  point.kind = motion.kind;
  point.feed = motion.feed;
  if (!started_) {
    started_ = true;
    point.p = motion.start;
    point.time = time_;
    emit(point, sink);
  }
  if (motion.kind == gcode::MotionKind::arc)
    add_arc(motion, point, sink);
  else
    add_line(motion, point, sink);
}

namespace {
// Seconds per mm at the motion's rate.
double seconds_per_mm(const gcode::Motion& motion, double rapid_rate) {
  const bool rapid = motion.kind == gcode::MotionKind::rapid || !(motion.feed > 0.0);
  return units::kSecondsPerMinute / (rapid ? rapid_rate : motion.feed);
}
}  // namespace

void Fragmenter::add_line(const gcode::Motion& motion, PathPoint& point, const PointSink& sink) {
  const LineSpan span(motion.start, motion.end);
  const double length = span.length();
  if (length == 0.0) return;
  const Eigen::Vector3d v = span.velocity();
  for (int k = 0; k < 3; ++k)
    if (v[k] != 0.0) dir_[static_cast<std::size_t>(k)] = sign(v[k]);
  const std::size_t n = segments(length, motion);
  const double dt = length / static_cast<double>(n) * seconds_per_mm(motion, options_.rapid_rate);
  const double t0 = time_;
  for (std::size_t i = 1; i <= n; ++i) {
    point.p = i == n ? motion.end : span.point(static_cast<double>(i) / static_cast<double>(n));
    point.time = t0 + static_cast<double>(i) * dt;
    emit(point, sink);
  }
  time_ = point.time;
}

void Fragmenter::add_arc(const gcode::Motion& motion, PathPoint& point, const PointSink& sink) {
  const ArcSpan span(motion);
  const double length = span.length();
  if (length == 0.0) return;
  const std::size_t n = segments(span.length_bound(), motion);
  const double dt = length / static_cast<double>(n) * seconds_per_mm(motion, options_.rapid_rate);
  const double t0 = time_;
  span.for_each_sample(n, [&](std::size_t i, const Eigen::Vector3d& p, const Eigen::Vector3d& v) {
    // |v_k| > tolerance·|v|, squared (no square root per point).
    const double tolerance2 = kDirectionTolerance * kDirectionTolerance * v.squaredNorm();
    for (int k = 0; k < 3; ++k)
      if (v[k] * v[k] > tolerance2) dir_[static_cast<std::size_t>(k)] = sign(v[k]);
    point.p = p;  // the end point exactly at i == n
    point.time = t0 + static_cast<double>(i) * dt;
    emit(point, sink);
  });
  time_ = point.time;
}

}  // namespace abbe::path
