#pragma once
// Fragmenter: splits each Motion into PathPoints at most `step` apart (lines
// by equal length, arcs and helices by equal arc length), keeping the exact
// end point of every motion, and estimates the time from the feeds (rapids at
// `rapid_rate`; dwells add time and emit no point). It keeps only the state of
// the previous motion, so a whole program streams through it.
//
// The point loops are templates on the sink (defined below): a lambda sink is
// inlined into them, so a point costs no indirect call (a PointSink works too).
// What runs once per motion (the number of points, the arc's geometry) stays
// out of line in fragmenter.cpp and arc_span.cpp.
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

#include "abbe/gcode/motion.hpp"
#include "abbe/path/arc_span.hpp"
#include "abbe/path/line_span.hpp"
#include "abbe/path/path_point.hpp"

namespace abbe::path {

struct FragmentOptions {
  double step = 5.0;            // mm, > 0
  double rapid_rate = 10000.0;  // mm/min, > 0; also used for a feed motion with feed 0
};

using PointSink = std::function<void(const PathPoint&)>;

class Fragmenter {
 public:
  // Throws std::invalid_argument for a non-positive or non-finite step or rate.
  explicit Fragmenter(FragmentOptions options);

  // Emits the points of `motion` in order: its start point too if it is the
  // first (non-dwell) motion, then the intermediate points and its end point
  // (bit-exactly motion.end). A zero-length motion emits no new point.
  // `sink`: callable as sink(const PathPoint&).
  template <class Sink>
  void add(const gcode::Motion& motion, Sink&& sink);

  double time() const { return time_; }           // s, estimated so far
  std::size_t points() const { return points_; }  // emitted so far
  const FragmentOptions& options() const { return options_; }

 private:
  template <class Sink>
  void add_line(const gcode::Motion& motion, PathPoint& point, Sink& sink);
  template <class Sink>
  void add_arc(const gcode::Motion& motion, PathPoint& point, Sink& sink);
  // Throws gcode::MotionRefused past 1e9 points for one motion (the interpreter
  // or the compensator turns it into an InputError at the motion's line).
  std::size_t segments(double length, const gcode::Motion& motion) const;
  // Seconds per mm at the motion's rate (rapids and feed 0 at the rapid rate).
  double seconds_per_mm(const gcode::Motion& motion) const;
  template <class Sink>
  void emit(PathPoint& point, Sink& sink) {
    point.dir = dir_;
    ++points_;
    sink(static_cast<const PathPoint&>(point));
  }
  static std::int8_t sign(double v) { return v > 0.0 ? std::int8_t{1} : std::int8_t{-1}; }

  // A velocity component smaller than this fraction of the speed counts as
  // zero (the axis keeps its previous direction sign).
  static constexpr double kDirectionTolerance = 1e-9;

  FragmentOptions options_;
  bool started_ = false;
  double time_ = 0.0;
  std::size_t points_ = 0;
  // Sign of the last nonzero motion of each axis.
  std::array<std::int8_t, 3> dir_{0, 0, 0};
};

template <class Sink>
void Fragmenter::add(const gcode::Motion& motion, Sink&& sink) {
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

template <class Sink>
void Fragmenter::add_line(const gcode::Motion& motion, PathPoint& point, Sink& sink) {
  const LineSpan span(motion.start, motion.end);
  const double length = span.length();
  if (length == 0.0) return;
  const Eigen::Vector3d v = span.velocity();
  for (int k = 0; k < 3; ++k)
    if (v[k] != 0.0) dir_[static_cast<std::size_t>(k)] = sign(v[k]);
  const std::size_t n = segments(length, motion);
  const double dt = length / static_cast<double>(n) * seconds_per_mm(motion);
  const double t0 = time_;
  for (std::size_t i = 1; i <= n; ++i) {
    point.p = i == n ? motion.end : span.point(static_cast<double>(i) / static_cast<double>(n));
    point.time = t0 + static_cast<double>(i) * dt;
    emit(point, sink);
  }
  time_ = point.time;
}

template <class Sink>
void Fragmenter::add_arc(const gcode::Motion& motion, PathPoint& point, Sink& sink) {
  const ArcSpan span(motion);
  const double length = span.length();
  if (length == 0.0) return;
  const std::size_t n = segments(span.length_bound(), motion);
  const double dt = length / static_cast<double>(n) * seconds_per_mm(motion);
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
