#include "abbe/machine/travel_check.hpp"

#include <fmt/format.h>

namespace abbe::machine {
namespace {
// Positions within this of a travel end count as inside (rounding of the
// program's numbers and of the tool length).
constexpr double kSlackMm = 1e-6;
constexpr char kAxis[3] = {'X', 'Y', 'Z'};
}  // namespace

TravelCheck::TravelCheck(const std::array<Travel, 3>& travel) : travel_(travel) {
  for (std::size_t a = 0; a < 3; ++a) {
    lo_[a] = travel_[a].min - kSlackMm;
    hi_[a] = travel_[a].max + kSlackMm;
  }
}

void TravelCheck::add_outside(const Eigen::Vector3d& s, std::size_t line) {
  for (std::size_t a = 0; a < 3; ++a)
    if (!inside(a, s[static_cast<Eigen::Index>(a)])) ++per_axis_[a];
  ++outside_;
  if (lines_.size() < 5 && (lines_.empty() || lines_.back() != line)) lines_.push_back(line);
}

std::string TravelCheck::text() const {
  if (!outside_) return "";
  std::string axes;
  for (std::size_t a = 0; a < 3; ++a)
    if (per_axis_[a])
      axes += fmt::format("{}{} {}", axes.empty() ? "" : ", ", kAxis[a], per_axis_[a]);
  std::string lines;
  for (auto l : lines_) lines += fmt::format("{}{}", lines.empty() ? "" : ", ", l);
  return fmt::format("{} of {} points outside the travel (points per axis: {}), first on lines {}",
                     outside_, points_, axes, lines);
}

std::string TravelCheck::describe(const Eigen::Vector3d& tip, double tool_length) const {
  const Eigen::Vector3d s = tip + Eigen::Vector3d(0.0, 0.0, tool_length);
  std::string out;
  for (std::size_t a = 0; a < 3; ++a) {
    const double v = s[static_cast<Eigen::Index>(a)];
    if (inside(a, v)) continue;
    out += fmt::format("{}{} axis at {:.4f} mm, travel [{:g}, {:g}] mm", out.empty() ? "" : "; ",
                       kAxis[a], v, travel_[a].min, travel_[a].max);
  }
  return out;
}

}  // namespace abbe::machine
