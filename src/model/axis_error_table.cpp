#include "abbe/model/axis_error_table.hpp"

#include <algorithm>
#include <limits>

namespace abbe::model {

using machine::ComponentId;
using machine::ComponentSeries;
using machine::TableDirection;

namespace {

// One series at s with the table's out-of-range rule.
double series_at(const ComponentSeries& c, double s, bool extrapolate) {
  const auto& x = c.position_mm;
  const auto& y = c.value;
  std::size_t n = x.size();
  if (n == 1) return y[0];
  if (!extrapolate) {
    if (s <= x.front()) return y.front();
    if (s >= x.back()) return y.back();
  }
  std::size_t i = static_cast<std::size_t>(std::upper_bound(x.begin(), x.end(), s) - x.begin());
  i = std::clamp<std::size_t>(i, 1, n - 1) - 1;
  double t = (s - x[i]) / (x[i + 1] - x[i]);
  return y[i] + t * (y[i + 1] - y[i]);
}

}  // namespace

AxisErrorTable AxisErrorTable::build(const machine::ComponentTable& table, machine::Axis axis,
                                     int dir, machine::OutOfRangePolicy policy) {
  AxisErrorTable out;
  out.extrapolate_ = policy == machine::OutOfRangePolicy::extrapolate;
  // The series that make up each of the six components (averaged).
  std::array<std::vector<const ComponentSeries*>, 6> parts;
  std::vector<double> grid;
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  for (int d = 0; d < machine::kComponentsPerAxis; ++d) {
    ComponentId id{axis, d};
    auto& p = parts[static_cast<std::size_t>(d)];
    if (const ComponentSeries* m = table.find(id, TableDirection::mean)) {
      p.push_back(m);
    } else if (table.find(id, TableDirection::fwd)) {
      if (dir >= 0) p.push_back(table.find(id, TableDirection::fwd));
      if (dir <= 0) p.push_back(table.find(id, TableDirection::rev));
    }
    for (const ComponentSeries* c : p) {
      if (!c) continue;
      grid.insert(grid.end(), c->position_mm.begin(), c->position_mm.end());
      lo = std::max(lo, c->position_mm.front());
      hi = std::min(hi, c->position_mm.back());
    }
  }
  if (grid.empty()) return out;
  std::sort(grid.begin(), grid.end());
  grid.erase(std::unique(grid.begin(), grid.end()), grid.end());
  out.lo_ = lo;
  out.hi_ = hi;
  out.s_ = grid;
  out.knots_.resize(grid.size());
  for (std::size_t g = 0; g < grid.size(); ++g)
    for (std::size_t d = 0; d < 6; ++d) {
      double sum = 0.0;
      for (const ComponentSeries* c : parts[d]) sum += series_at(*c, grid[g], out.extrapolate_);
      out.knots_[g].value[d] = parts[d].empty() ? 0.0 : sum / static_cast<double>(parts[d].size());
    }
  for (std::size_t g = 0; g < grid.size(); ++g)
    for (std::size_t d = 0; d < 6; ++d)
      out.knots_[g].slope[d] =
          g + 1 < grid.size()
              ? (out.knots_[g + 1].value[d] - out.knots_[g].value[d]) / (grid[g + 1] - grid[g])
              : 0.0;
  // Extrapolation past the last knot continues the last segment.
  if (grid.size() >= 2) out.knots_.back().slope = out.knots_[grid.size() - 2].slope;
  out.s0_ = grid.front();
  out.last_ = grid.size() >= 2 ? grid.size() - 2 : 0;
  out.last_d_ = static_cast<double>(out.last_);
  out.inv_step_ = grid.size() >= 2 ? 1.0 / (grid[1] - grid[0]) : 0.0;
  const double inf = std::numeric_limits<double>::infinity();
  out.clamp_lo_ = out.extrapolate_ ? -inf : grid.front();
  out.clamp_hi_ = out.extrapolate_ ? inf : grid.back();
  return out;
}

// Off the guessed segment (uneven spacing or rounding): step towards x, then
// bisect if it is far.
std::size_t AxisErrorTable::step_down(double x, std::size_t i) const {
  for (int n = 0; n < 4; ++n) {
    --i;
    if (i == 0 || x >= s_[i]) return i;
  }
  const auto j = static_cast<std::size_t>(
      std::upper_bound(s_.begin(), s_.begin() + static_cast<std::ptrdiff_t>(i) + 1, x) -
      s_.begin());
  return j == 0 ? 0 : j - 1;
}

std::size_t AxisErrorTable::step_up(double x, std::size_t i) const {
  for (int n = 0; n < 4; ++n) {
    ++i;
    if (i == last_ || x < s_[i + 1]) return i;
  }
  const auto j = static_cast<std::size_t>(
      std::upper_bound(s_.begin() + static_cast<std::ptrdiff_t>(i) + 1,
                       s_.begin() + static_cast<std::ptrdiff_t>(last_) + 1, x) -
      s_.begin());
  return j - 1;
}

}  // namespace abbe::model
