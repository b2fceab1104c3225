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
  return out;
}

std::size_t AxisErrorTable::find_segment(double s, TableCursor& cursor) const {
  // Segments are [s_i, s_{i+1}], i = 0..n-2. Walk a few steps from the last
  // one, then fall back to bisection.
  std::size_t last = s_.size() - 2;
  std::size_t i = std::min(cursor.segment, last);
  for (int step = 0; step < 4; ++step) {
    if (s < s_[i]) {
      if (i == 0) return cursor.segment = 0;
      --i;
    } else if (s > s_[i + 1]) {
      if (i == last) return cursor.segment = last;
      ++i;
    } else {
      return cursor.segment = i;
    }
  }
  std::size_t j = static_cast<std::size_t>(std::upper_bound(s_.begin(), s_.end(), s) - s_.begin());
  return cursor.segment = std::clamp<std::size_t>(j, 1, last + 1) - 1;
}

bool AxisErrorTable::eval_general(double s, TableCursor& cursor, AxisErrors& out) const {
  if (knots_.empty()) {
    out.delta_um.setZero();
    out.theta_urad.setZero();
    return true;
  }
  bool inside = s >= lo_ && s <= hi_;
  const Knot* k;
  double t;
  if (s_.size() == 1) {
    k = &knots_[0];
    t = 0.0;
  } else if (!extrapolate_ && s <= s_.front()) {
    k = &knots_.front();
    t = 0.0;
  } else if (!extrapolate_ && s >= s_.back()) {
    k = &knots_.back();
    t = 0.0;
  } else {
    std::size_t i = find_segment(s, cursor);
    k = &knots_[i];
    t = s - s_[i];
  }
  for (int d = 0; d < 3; ++d) {
    out.delta_um[d] =
        k->value[static_cast<std::size_t>(d)] + t * k->slope[static_cast<std::size_t>(d)];
    out.theta_urad[d] =
        k->value[static_cast<std::size_t>(d + 3)] + t * k->slope[static_cast<std::size_t>(d + 3)];
  }
  return inside;
}

}  // namespace abbe::model
