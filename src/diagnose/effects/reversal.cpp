// reversal: a jump when an axis reverses (backlash, lost motion); with
// `degree` 1 the jump changes linearly along the axis's travel (a screw or
// guideway worn unevenly: ISO 230-2 reports the reversal B_i at every
// target for this reason).
#include <fmt/format.h>

#include "builtin_effects.hpp"

namespace abbe::diagnose::effects {
namespace {
bool growing(const Term& t) { return t.degree >= 1; }
}  // namespace

EffectDescriptor reversal() {
  EffectDescriptor d = make_descriptor(TermKind::reversal, "reversal", "reversal");
  // Bounded (± half the reversal); a growing one is linear in the position
  // beyond the domain, as a scale is.
  d.extrapolates = true;
  d.columns = [](const Term& t) { return growing(t) ? 2 : 1; };
  d.basis = [](const Term& t, const PointContext& pc, BasisOut out) {
    const double half_step = 0.5 * static_cast<double>(pc.dir[static_cast<std::size_t>(t.axis)]);
    out(t.direction, 0) = half_step;
    // The growth: the jump's change from the travel's middle to its end.
    if (growing(t))
      out(t.direction, 1) = half_step * (pc.s[t.axis] - t.centre[t.axis]) / t.half[t.axis];
  };
  d.label = [](const Term& t) {
    return growing(t) ? fmt::format("reversal {}→{} growing along {}", axis_name(t.axis),
                                    axis_name(t.direction), variable_name(t.axis))
                      : fmt::format("reversal {}→{}", axis_name(t.axis), axis_name(t.direction));
  };
  d.description = [](const Term& t) {
    if (growing(t)) {
      // The growth with its standard uncertainty where the fit gave one (the
      // text table's value column holds the jump's).
      const std::string growth =
          t.stderr_.size() > 1 && t.stderr_[1] > 0.0
              ? fmt::format("{:+.2f} ± {:.2g}", coef_or_zero(t, 1), t.stderr_[1])
              : fmt::format("{:+.2f}", coef_or_zero(t, 1));
      return fmt::format(
          "{} jumps by {:+.2f} µm when {} reverses at {} = {:.1f} mm, {} µm more at the "
          "travel's end ({} = {:.1f} mm): backlash / lost motion that changes along the travel "
          "(uneven wear)",
          axis_name(t.direction), coef_or_zero(t, 0), axis_name(t.axis), variable_name(t.axis),
          t.centre[t.axis], growth, variable_name(t.axis), t.centre[t.axis] + t.half[t.axis]);
    }
    return fmt::format("{} jumps by {:+.2f} µm when {} reverses: backlash / lost motion",
                       axis_name(t.direction), coef_or_zero(t, 0), axis_name(t.axis));
  };
  d.params = [](const Term& t) -> NamedValues {
    if (growing(t)) return {{"um", coef_or_zero(t, 0)}, {"growth_um", coef_or_zero(t, 1)}};
    return {{"um", coef_or_zero(t, 0)}};
  };
  d.param_stderr = [](const Term& t) -> NamedValues {
    auto se = [&](std::size_t i) { return i < t.stderr_.size() ? t.stderr_[i] : 0.0; };
    if (growing(t)) return {{"um", se(0)}, {"growth_um", se(1)}};
    return {{"um", se(0)}};
  };
  // A growing reversal's overlay entry records where its growth is zero and
  // what its unit is: `centre` and `half` (mm, all three axes, as a
  // coupling's) and `growing: true`.
  d.read_fields = [](Term& t, const OverlayFields& in) {
    if (!in.has("growing")) return;
    const std::string g = in.text("growing");
    if (g == "false") return;
    if (g != "true") in.fail("growing", "growing must be true or false");
    t.degree = 1;
    t.centre = read_point(in, "centre");
    t.half = read_point(in, "half");
    for (int k = 0; k < 3; ++k)
      if (!(t.half[k] > 0.0)) in.fail("half", "half ranges must be positive");
  };
  d.write_fields = [](const Term& t, std::string& y) {
    if (!growing(t)) return;
    y += fmt::format("    growing: true\n    centre: {}\n    half: {}\n",
                     yaml_list(t.centre.data(), 3), yaml_list(t.half.data(), 3));
  };
  return d;
}

}  // namespace abbe::diagnose::effects
