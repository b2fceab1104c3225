// thermal_drift: a deviation growing with time (1 − e^(−t/τ), or t per hour
// for τ = 0), optionally in proportion to an axis position.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "abbe/io/units.hpp"
#include "builtin_effects.hpp"

namespace abbe::diagnose::effects {
namespace {
// τ = 0 is the drift linear in time (per hour), named so ("τ 0 s" would
// read as an instant step).
std::string time_law(const Term& t) {
  return t.tau_s > 0.0 ? fmt::format("τ {:.0f} s", t.tau_s) : std::string("linear in t");
}
// The name of the first parameter (the drift's size).
const char* size_name(const Term& t) {
  return t.with_axis >= 0 ? "ppm" : (t.tau_s > 0.0 ? "um" : "um_per_h");
}
// The same with τ's standard uncertainty where the fit gave one.
std::string time_law_with_u(const Term& t) {
  if (!(t.tau_s > 0.0) || !(t.searched_stderr > 0.0)) return time_law(t);
  return fmt::format("τ {:.0f} ± {:.2g} s", t.tau_s, t.searched_stderr);
}
}  // namespace

EffectDescriptor thermal_drift() {
  EffectDescriptor d = make_descriptor(TermKind::thermal_drift, "thermal_drift", "thermal_drift");
  d.basis = [](const Term& t, const PointContext& pc, BasisOut out) {
    const double time = std::max(pc.t, 0.0);
    double f = t.tau_s > 0.0 ? 1.0 - std::exp(-time / t.tau_s) : time / units::kSecondsPerHour;
    if (t.with_axis >= 0) f *= units::kMmPerUm * pc.s[t.with_axis];
    out(t.direction, 0) = f;
  };
  d.label = [](const Term& t) {
    const char dir = axis_name(t.direction);
    return t.with_axis >= 0 ? fmt::format("thermal_drift {}·t→{} ({})", variable_name(t.with_axis),
                                          dir, time_law(t))
                            : fmt::format("thermal_drift t→{} ({})", dir, time_law(t));
  };
  d.description = [](const Term& t) {
    const char dir = axis_name(t.direction);
    if (t.with_axis >= 0)
      return fmt::format(
          "{} grows with time ∝ {} ({:+.2f} ppm{}, {}): thermal expansion during "
          "warm-up",
          dir, variable_name(t.with_axis), coef_or_zero(t, 0), t.tau_s > 0.0 ? "" : " per hour",
          time_law_with_u(t));
    return fmt::format("{} drifts with time ({:+.2f} µm{}, {}): warm-up, spindle growth", dir,
                       coef_or_zero(t, 0), t.tau_s > 0.0 ? "" : " per hour", time_law_with_u(t));
  };
  d.params = [](const Term& t) -> NamedValues {
    return {{size_name(t), coef_or_zero(t, 0)}, {"tau_s", t.tau_s}};
  };
  d.param_stderr = [](const Term& t) -> NamedValues {
    NamedValues out{{size_name(t), t.stderr_.empty() ? 0.0 : t.stderr_[0]}};
    if (t.tau_s > 0.0) out.emplace_back("tau_s", t.searched_stderr);
    return out;
  };
  d.read_fields = [](Term& t, const OverlayFields& in) {
    t.tau_s = in.number("tau_s");
    if (t.tau_s < 0.0) in.fail("tau_s", "tau_s must be ≥ 0 (0: linear in t)");
    if (in.has("with")) t.with_axis = in.axis("with");
  };
  d.write_fields = [](const Term& t, std::string& y) {
    y += fmt::format("    tau_s: {:.17g}\n", t.tau_s);
  };
  return d;
}

}  // namespace abbe::diagnose::effects
