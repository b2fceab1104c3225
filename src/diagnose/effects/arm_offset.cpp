// arm_offset: the angular errors of an axis act with a longer arm than the
// model's (wrong tool length or reflector position): ε_j × Δ.
#include <fmt/format.h>

#include <Eigen/Geometry>  // cross()

#include "abbe/io/units.hpp"
#include "builtin_effects.hpp"

namespace abbe::diagnose::effects {

EffectDescriptor arm_offset() {
  EffectDescriptor d = make_descriptor(TermKind::arm_offset, "arm_offset", "arm_offset");
  d.extrapolates = true;  // ε_j from the tables (their own out-of-range policy)
  d.basis = [](const Term& t, const PointContext& pc, BasisOut out) {
    // ε_j × Δ with Δ = e_k (mm): µrad·mm = 1e-3 µm
    out.col(0) = units::kUmPerUradMm * pc.eps_urad[static_cast<std::size_t>(t.axis)].cross(
                                           Eigen::Vector3d::Unit(t.direction));
  };
  d.label = [](const Term& t) {
    return fmt::format("arm_offset ε{}×Δ{}", axis_name(t.axis), axis_name(t.direction));
  };
  d.description = [](const Term& t) {
    return fmt::format(
        "angular errors of {} act with an arm {:+.2f} mm longer along {}: wrong "
        "tool length or reflector position",
        axis_name(t.axis), coef_or_zero(t, 0), axis_name(t.direction));
  };
  d.params = [](const Term& t) -> NamedValues { return {{"mm", coef_or_zero(t, 0)}}; };
  return d;
}

}  // namespace abbe::diagnose::effects
