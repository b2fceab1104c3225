// coupling: a deviation in proportion to the product of two axis positions,
// each scaled to [−1, 1] over its travel (sag, bending, guideways).
#include <fmt/format.h>

#include "builtin_effects.hpp"

namespace abbe::diagnose::effects {

EffectDescriptor coupling() {
  EffectDescriptor d = make_descriptor(TermKind::coupling, "coupling", "coupling");
  d.basis = [](const Term& t, const PointContext& pc, BasisOut out) {
    out(t.direction, 0) = (pc.s[t.axis] - t.centre[t.axis]) / t.half[t.axis] *
                          (pc.s[t.with_axis] - t.centre[t.with_axis]) / t.half[t.with_axis];
  };
  d.label = [](const Term& t) {
    return fmt::format("coupling {}·{}→{}", variable_name(t.axis), variable_name(t.with_axis),
                       axis_name(t.direction));
  };
  d.description = [](const Term& t) {
    return fmt::format(
        "{} depends on the product of {} and {} ({:+.2f} µm at the travel "
        "corners): sag, bending, non-rigid guideways",
        axis_name(t.direction), variable_name(t.axis), variable_name(t.with_axis),
        coef_or_zero(t, 0));
  };
  d.params = [](const Term& t) -> NamedValues { return {{"um", coef_or_zero(t, 0)}}; };
  d.read_fields = [](Term& t, const OverlayFields& in) {
    t.with_axis = in.axis("with");
    if (t.with_axis == t.axis) in.fail("with", "coupling needs two different axes");
    const auto c = in.numbers("centre");
    const auto h = in.numbers("half");
    if (c.size() != 3 || h.size() != 3) in.fail_entry("centre", "centre and half need 3 numbers");
    for (int k = 0; k < 3; ++k) {
      t.centre[k] = c[static_cast<std::size_t>(k)];
      t.half[k] = h[static_cast<std::size_t>(k)];
      if (!(t.half[k] > 0.0)) in.fail("half", "half ranges must be positive");
    }
  };
  d.write_fields = [](const Term& t, std::string& y) {
    y += fmt::format("    centre: {}\n    half: {}\n", yaml_list(t.centre.data(), 3),
                     yaml_list(t.half.data(), 3));
  };
  return d;
}

}  // namespace abbe::diagnose::effects
