#include "abbe/path/fragmenter.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "abbe/gcode/motion_limits.hpp"
#include "abbe/io/units.hpp"

namespace abbe::path {

namespace {
// More segments than this for one motion means a step far below any
// machine's resolution: refused rather than looping for hours.
constexpr double kMaxSegments = 1e9;
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

double Fragmenter::seconds_per_mm(const gcode::Motion& motion) const {
  const bool rapid = motion.kind == gcode::MotionKind::rapid || !(motion.feed > 0.0);
  return units::kSecondsPerMinute / (rapid ? options_.rapid_rate : motion.feed);
}

}  // namespace abbe::path
