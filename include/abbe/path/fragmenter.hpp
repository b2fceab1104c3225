#pragma once
// Fragmenter: splits each Motion into PathPoints at most `step` apart (arcs
// and helices by equal arc length), keeping exact end points, and estimates
// time from feeds (rapids at `rapid_rate`).
#include <functional>

#include "abbe/gcode/motion.hpp"
#include "abbe/path/path_point.hpp"

namespace abbe::path {

struct FragmentOptions {
  double step = 5.0;            // mm
  double rapid_rate = 10000.0;  // mm/min
};

using PointSink = std::function<void(const PathPoint&)>;

class Fragmenter {
 public:
  explicit Fragmenter(FragmentOptions options);
  // Emits the points of `motion` (its start point too, for the first motion).
  void add(const gcode::Motion& motion, const PointSink& sink);

 private:
  FragmentOptions options_;
  bool started_ = false;
  double time_ = 0.0;
  std::array<std::int8_t, 3> dir_{0, 0, 0};
};

}  // namespace abbe::path
