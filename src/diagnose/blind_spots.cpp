#include "abbe/diagnose/blind_spots.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "abbe/diagnose/term.hpp"
#include "coverage.hpp"

namespace abbe::diagnose {

std::vector<BlindSpot> blind_spots(const Problem& pb, const DesignAmbiguityOptions& design,
                                   double min_period_mm, double max_period_mm,
                                   double max_period_span_share) {
  std::vector<BlindSpot> out;
  if (pb.obs.empty()) return out;
  const Coverage seen(pb);
  auto present = [&](std::size_t i) { return pb.direction_present[i]; };

  for (std::size_t i = 0; i < 3; ++i)
    if (!present(i))
      out.push_back({fmt::format("every effect in {} (d{})", axis_name(static_cast<int>(i)),
                                 variable_name(static_cast<int>(i))),
                     fmt::format("d{} is not measured", variable_name(static_cast<int>(i))),
                     fmt::format("measure d{} as well", variable_name(static_cast<int>(i)))});
  if (!seen.varies(3))
    out.push_back({"a drift in time (thermal_drift)",
                   "the data have no time (t is the same for every point)",
                   "record the time of each point (t, s since the start)"});
  for (std::size_t j = 0; j < 3; ++j) {
    const int a = static_cast<int>(j);
    if (!seen.varies(a)) {
      out.push_back(
          {fmt::format("every effect that varies with {} (scale, squareness, cycles, couplings "
                       "with {})",
                       variable_name(a), variable_name(a)),
           fmt::format("{} stands at one position ({} = {:.6g} mm)", axis_name(a), variable_name(a),
                       seen.tip_lo(a)),
           fmt::format("measure at a second {} position (another plane)", axis_name(a))});
    } else {
      for (std::size_t i = 0; i < 3; ++i)
        if (present(i) && !seen.varies_in(a, static_cast<int>(i)))
          out.push_back(
              {fmt::format("d{} as a function of {} (squareness or scale {}→{}, its cycles, "
                           "couplings with {})",
                           variable_name(static_cast<int>(i)), variable_name(a), axis_name(a),
                           axis_name(static_cast<int>(i)), variable_name(a)),
               fmt::format("d{} is measured at one {} only", variable_name(static_cast<int>(i)),
                           variable_name(a)),
               fmt::format("measure d{} at several {} positions",
                           variable_name(static_cast<int>(i)), axis_name(a))});
    }
    // A short travel: the catalogue's longer periods are not held twice
    // (candidates.cpp scans up to max_period_span_share of the span).
    const double span = pb.var_hi[j] - pb.var_lo[j];
    if (seen.varies(a) && span > 0.0 && max_period_span_share * span < max_period_mm)
      out.push_back(
          {fmt::format("a cycle of {} longer than {:.4g} mm (a pitch error, a long wave)",
                       axis_name(a), max_period_span_share * span),
           fmt::format("{} spans {:.4g} mm: a longer period is not seen twice, and a part of it "
                       "is a slope or a bow of {}",
                       axis_name(a), span, axis_name(a)),
           fmt::format("measure over a longer travel of {} (a larger circle, a longer line)",
                       axis_name(a))});
    // (An axis at one position, approached one way, makes a reversal of it
    // a constant: the datum's, said above.)
    if (!seen.reverses(a) && seen.varies(a))
      out.push_back(
          {fmt::format("a reversal of {} (backlash)", axis_name(a)),
           !seen.has_direction(a)
               ? fmt::format("the data carry no approach direction of {} (v{} is 0 or missing)",
                             axis_name(a), variable_name(a))
               : fmt::format("{} approaches every point from one side", axis_name(a)),
           !seen.has_direction(a)
               ? fmt::format("record v{}, the sign of {}'s last motion at each point",
                             variable_name(a), axis_name(a))
               : fmt::format("approach the points from both sides in {}", axis_name(a))});
  }
  const auto levels = levelled_axes(pb, design, min_period_mm);
  for (std::size_t j = 0; j < 3; ++j) {
    const std::vector<double>& lv = levels[j];
    if (lv.empty()) continue;
    double gap = 1e300;
    for (std::size_t l = 1; l < lv.size(); ++l) gap = std::min(gap, lv[l] - lv[l - 1]);
    const int a = static_cast<int>(j);
    out.push_back(
        {2.0 * gap > max_period_mm
             ? fmt::format("a cycle of {} (a pitch error; every period of the catalogue, {:.4g}–"
                           "{:.4g} mm)",
                           axis_name(a), min_period_mm, max_period_mm)
             : fmt::format("a cycle of {} shorter than {:.4g} mm (a pitch error)", axis_name(a),
                           2.0 * gap),
         fmt::format("{} stands on {} levels {:.4g} mm or more apart: they alias every shorter "
                     "period{}",
                     axis_name(a), lv.size(), gap,
                     lv.size() >= design.period_only_min_levels
                         ? " (where no smooth function follows its samples, a cycle's kind is "
                           "still named, its period not)"
                         : ""),
         fmt::format("sample {} at irregular spacing", axis_name(a))});
  }
  return out;
}

}  // namespace abbe::diagnose
