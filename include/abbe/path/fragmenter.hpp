#pragma once
// Fragmenter: splits each Motion into PathPoints at most `step` apart (lines
// by equal length, arcs and helices by equal arc length), keeping the exact
// end point of every motion, and estimates the time from the feeds (rapids at
// `rapid_rate`; dwells add time and emit no point). It keeps only the state of
// the previous motion, so a whole program streams through it.
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

#include "abbe/gcode/motion.hpp"
#include "abbe/path/path_point.hpp"

namespace abbe::path {

struct FragmentOptions {
  double step = 5.0;               // mm, > 0
  double rapid_rate = 10000.0;     // mm/min, > 0; also used for a feed motion with feed 0
};

using PointSink = std::function<void(const PathPoint&)>;

class Fragmenter {
 public:
  // Throws std::invalid_argument for a non-positive or non-finite step or rate.
  explicit Fragmenter(FragmentOptions options);

  // Emits the points of `motion` in order: its start point too if it is the
  // first (non-dwell) motion, then the intermediate points and its end point
  // (bit-exactly motion.end). A zero-length motion emits no new point.
  void add(const gcode::Motion& motion, const PointSink& sink);

  double time() const { return time_; }           // s, estimated so far
  std::size_t points() const { return points_; }  // emitted so far
  const FragmentOptions& options() const { return options_; }

 private:
  void add_line(const gcode::Motion& motion, PathPoint& point, const PointSink& sink);
  void add_arc(const gcode::Motion& motion, PathPoint& point, const PointSink& sink);
  // Throws gcode::MotionRefused past 1e9 points for one motion (the interpreter
  // or the compensator turns it into an InputError at the motion's line).
  std::size_t segments(double length, const gcode::Motion& motion) const;
  void emit(PathPoint& point, const PointSink& sink);

  FragmentOptions options_;
  bool started_ = false;
  double time_ = 0.0;
  std::size_t points_ = 0;
  // Sign of the last nonzero motion of each axis.
  std::array<std::int8_t, 3> dir_{0, 0, 0};
};

}  // namespace abbe::path
