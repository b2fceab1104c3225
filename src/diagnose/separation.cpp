#include "abbe/diagnose/separation.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace abbe::diagnose {
namespace {

bool depends_on_time(const Term& t) {
  if (t.kind == TermKind::thermal_drift) return true;
  if (t.kind == TermKind::unexplained)
    return std::find(t.vars.begin(), t.vars.end(), 3) != t.vars.end();
  return false;
}

// The axes whose positions drive the term (none for setup and model terms).
std::vector<int> driving_axes(const Term& t) {
  switch (t.kind) {
    case TermKind::unexplained: {
      std::vector<int> a;
      for (int v : t.vars)
        if (v < 3) a.push_back(v);
      return a;
    }
    case TermKind::coupling:
      return {t.axis, t.with_axis};
    case TermKind::thermal_drift:
      return t.with_axis >= 0 ? std::vector<int>{t.with_axis} : std::vector<int>{};
    case TermKind::setup_offset:
    case TermKind::setup_rotation:
    case TermKind::model_choice:
      return {};
    default:
      return t.axis >= 0 ? std::vector<int>{t.axis} : std::vector<int>{};
  }
}

}  // namespace

std::string separating_measurement(const Term& chosen, const std::vector<Term>& rivals,
                                   const std::vector<double>& aliased_periods) {
  if (!aliased_periods.empty()) {
    std::string periods = fmt::format("{:g}", chosen.period_mm);
    for (double p : aliased_periods) periods += fmt::format(", {:g}", p);
    return fmt::format(
        "sample {} at irregular spacing (periods of {} mm give the same samples "
        "on these points)",
        axis_name(chosen.axis), periods);
  }
  if (rivals.empty()) return "";
  // d_i ∝ s_j against d_j ∝ s_i: they differ by a rotation about the third
  // axis only, so they fit alike where the data do not fix that rotation (it
  // is in the datum of a re-placed plate): one out-of-squareness of the two
  // axes either way.
  for (const Term& r : rivals)
    if (chosen.kind == TermKind::squareness && r.kind == TermKind::squareness &&
        r.axis == chosen.direction && r.direction == chosen.axis && chosen.axis >= 0 &&
        chosen.direction >= 0)
      return fmt::format(
          "d{} ∝ {} and d{} ∝ {} differ by a rotation about {} alone, which these data do not fix "
          "(e.g. the fitted rotation of a re-placed plate): both are one out-of-squareness of {} "
          "and {}; to say which axis is off, measure the direction of {} or of {} against a "
          "reference",
          axis_name(chosen.direction), variable_name(chosen.axis), axis_name(r.direction),
          variable_name(r.axis), axis_name(3 - chosen.axis - chosen.direction),
          axis_name(chosen.axis), axis_name(chosen.direction), axis_name(chosen.axis),
          axis_name(chosen.direction));
  for (const Term& r : rivals)
    if (depends_on_time(r) != depends_on_time(chosen))
      return "measure the points again in another order or after a pause (in this design time "
             "and position vary together)";
  const std::vector<int> mine = driving_axes(chosen);
  for (const Term& r : rivals) {
    for (int a : driving_axes(r)) {
      if (a < 0 || std::find(mine.begin(), mine.end(), a) != mine.end()) continue;
      for (int b : mine)
        if (b >= 0)
          return fmt::format("measure points where {} and {} vary apart (here they move together)",
                             axis_name(b), axis_name(a));
    }
  }
  return "measure where these explanations differ: on these points their fitted contributions "
         "coincide";
}

}  // namespace abbe::diagnose
