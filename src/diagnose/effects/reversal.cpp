// reversal: a jump when an axis reverses (backlash, lost motion).
#include <fmt/format.h>

#include "builtin_effects.hpp"

namespace abbe::diagnose::effects {

EffectDescriptor reversal() {
  EffectDescriptor d = make_descriptor(TermKind::reversal, "reversal", "reversal");
  d.extrapolates = true;  // bounded: ± half the reversal
  d.basis = [](const Term& t, const PointContext& pc, BasisOut out) {
    out(t.direction, 0) = 0.5 * static_cast<double>(pc.dir[static_cast<std::size_t>(t.axis)]);
  };
  d.label = [](const Term& t) {
    return fmt::format("reversal {}→{}", axis_name(t.axis), axis_name(t.direction));
  };
  d.description = [](const Term& t) {
    return fmt::format("{} jumps by {:+.2f} µm when {} reverses: backlash / lost motion",
                       axis_name(t.direction), coef_or_zero(t, 0), axis_name(t.axis));
  };
  d.params = [](const Term& t) -> NamedValues { return {{"um", coef_or_zero(t, 0)}}; };
  return d;
}

}  // namespace abbe::diagnose::effects
