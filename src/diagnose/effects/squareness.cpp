// squareness: the deviation along one axis grows with another's position.
#include <fmt/format.h>

#include "abbe/io/units.hpp"
#include "builtin_effects.hpp"

namespace abbe::diagnose::effects {

EffectDescriptor squareness() {
  EffectDescriptor d = make_descriptor(TermKind::squareness, "squareness", "squareness");
  d.extrapolates = true;  // linear in the position, as a squareness is
  d.basis = [](const Term& t, const PointContext& pc, BasisOut out) {
    out(t.direction, 0) = units::kMmPerUm * pc.s[t.axis];  // coefficient in µrad
  };
  d.label = [](const Term& t) {
    return fmt::format("squareness d{} ∝ {}", axis_name(t.direction), variable_name(t.axis));
  };
  d.description = [](const Term& t) {
    return fmt::format(
        "{} deviation grows with {} by {:+.2f} µrad: axis misalignment "
        "(squareness) drift",
        axis_name(t.direction), variable_name(t.axis), coef_or_zero(t, 0));
  };
  d.params = [](const Term& t) -> NamedValues { return {{"urad", coef_or_zero(t, 0)}}; };
  return d;
}

}  // namespace abbe::diagnose::effects
