// scale: positions of an axis scale (thermal expansion, laser compensation).
#include <fmt/format.h>

#include "abbe/io/units.hpp"
#include "builtin_effects.hpp"

namespace abbe::diagnose::effects {

EffectDescriptor scale() {
  EffectDescriptor d = make_descriptor(TermKind::scale, "scale", "scale");
  d.extrapolates = true;  // linear in the position, as a scale error is
  d.basis = [](const Term& t, const PointContext& pc, BasisOut out) {
    out(t.direction, 0) = units::kMmPerUm * pc.s[t.axis];  // coefficient in µm/m (ppm)
  };
  d.label = [](const Term& t) { return fmt::format("scale {}", axis_name(t.axis)); };
  d.description = [](const Term& t) {
    return fmt::format(
        "{} positions scale by {:+.2f} ppm: thermal expansion or laser "
        "compensation error",
        axis_name(t.axis), coef_or_zero(t, 0));
  };
  d.params = [](const Term& t) -> NamedValues { return {{"ppm", coef_or_zero(t, 0)}}; };
  return d;
}

}  // namespace abbe::diagnose::effects
