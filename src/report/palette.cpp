#include "abbe/report/palette.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "abbe/report/svg.hpp"

namespace abbe::report::palette {
namespace {

std::string mix(const std::array<int, 3>& a, const std::array<int, 3>& b, double f) {
  std::array<int, 3> c{};
  for (std::size_t k = 0; k < 3; ++k)
    c[k] = static_cast<int>(std::lround(a[k] + f * (b[k] - a[k])));
  return fmt::format("#{:02x}{:02x}{:02x}", c[0], c[1], c[2]);
}

}  // namespace

std::string model_colour(model::ModelKind k) {
  switch (k) {
    case model::ModelKind::htm:
      return kOrange;
    case model::ModelKind::ae_arm:
      return kBlue;
    case model::ModelKind::dual:
      return kPurple;
  }
  return series_colour(static_cast<std::size_t>(k));
}

std::string tolerance_colour(double r) {
  if (std::isnan(r)) return "#999999";
  r = std::max(r, 0.0);
  if (r <= 1.0) return mix({198, 219, 239}, {8, 48, 107}, r);      // light → dark blue
  if (r <= 2.0) return mix({230, 159, 0}, {213, 94, 0}, r - 1.0);  // orange → vermilion
  return "#7f2704";                                                // dark brown
}

}  // namespace abbe::report::palette
