#include "box_option.hpp"

#include <fmt/format.h>

#include "interpreter_options.hpp"

namespace abbe::cli {

void parse_box_option(const std::vector<double>& values, Eigen::Vector3d& lo, Eigen::Vector3d& hi) {
  if (values.size() != 6)
    bad_option("--box",
               fmt::format("expected 6 numbers x0,y0,z0,x1,y1,z1 (mm), got {}", values.size()));
  Eigen::Vector3d a(values[0], values[1], values[2]), b(values[3], values[4], values[5]);
  for (int i = 0; i < 3; ++i)
    if (!(a[i] <= b[i]))
      bad_option("--box", fmt::format("{0}0 = {1:g} is greater than {0}1 = {2:g}: --box takes the "
                                      "two corners x0,y0,z0,x1,y1,z1 (lowest corner first), "
                                      "not min/max pairs",
                                      "xyz"[i], a[i], b[i]));
  lo = a;
  hi = b;
}

}  // namespace abbe::cli
