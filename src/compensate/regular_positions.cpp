// regular_positions: the evenly spaced positions of a controller table
// along one axis (controller_tables.hpp).
#include <fmt/format.h>

#include <cmath>

#include "abbe/compensate/controller_tables.hpp"
#include "abbe/io/input_error.hpp"

namespace abbe::compensate {

std::vector<double> regular_positions(double lo, double hi, double step, std::size_t count,
                                      std::size_t max_points, const std::string& option) {
  const SourceLocation where{"<command line>", 0, 0, option, ""};
  const double span = hi - lo;
  std::size_t n = 0;
  if (count > 0) {
    if (count < 2)
      throw InputError(where, fmt::format("{} nodes: a table needs at least 2", count));
    if (count > max_points)
      throw InputError(where, fmt::format("{} nodes: at most {}", count, max_points));
    n = count;
  } else {
    if (!(step > 0.0) || !std::isfinite(step))
      throw InputError(where, fmt::format("step {} mm: must be a positive number", step));
    // The number of intervals, computed in double first so that a tiny step
    // is refused instead of overflowing the cast.
    const double intervals = std::ceil(span / step - 1e-9);
    if (intervals + 1.0 > static_cast<double>(max_points))
      throw InputError(where, fmt::format("step {} mm gives {:.0f} positions over {} mm of "
                                          "travel: at most {} (a step of {} mm or more)",
                                          step, intervals + 1.0, span, max_points,
                                          span / static_cast<double>(max_points - 1)));
    n = intervals < 1.0 ? 2 : static_cast<std::size_t>(intervals) + 1;
  }
  if (!(span > 0.0)) return {lo};
  std::vector<double> out(n);
  const double h = span / static_cast<double>(n - 1);
  for (std::size_t i = 0; i < n; ++i) out[i] = lo + h * static_cast<double>(i);
  out.back() = hi;
  return out;
}

}  // namespace abbe::compensate
