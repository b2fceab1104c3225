#include "level_span.hpp"

#include <algorithm>

namespace abbe::diagnose::design {

std::size_t level_index(const std::vector<double>& lv, double s) {
  const auto l =
      static_cast<std::size_t>(std::lower_bound(lv.begin(), lv.end(), s - 1e-3) - lv.begin());
  return std::min(l, lv.size() - 1);
}

std::vector<double> levels_of(std::vector<double> v, const DesignAmbiguityOptions& o,
                              double min_period_mm) {
  std::sort(v.begin(), v.end());
  std::vector<double> levels;
  for (double x : v) {
    if (levels.empty() || x - levels.back() > 1e-3) levels.push_back(x);
    if (levels.size() > o.max_levels) break;
  }
  if (levels.size() < 3 || levels.size() > o.max_levels) return {};
  double gap = 1e300;
  for (std::size_t l = 1; l < levels.size(); ++l) gap = std::min(gap, levels[l] - levels[l - 1]);
  return gap >= 2.0 * min_period_mm ? levels : std::vector<double>{};
}

}  // namespace abbe::diagnose::design
