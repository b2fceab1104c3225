// cyclic: a sine of an axis position with a fixed period (ballscrew pitch
// error between the table's points); two columns, sin and cos.
#include <fmt/format.h>

#include <cmath>

#include "abbe/io/units.hpp"
#include "builtin_effects.hpp"

namespace abbe::diagnose::effects {

EffectDescriptor cyclic() {
  EffectDescriptor d = make_descriptor(TermKind::cyclic, "cyclic", "cyclic");
  d.extrapolates = true;  // bounded: the same wave beyond the domain
  d.columns = [](const Term&) { return 2; };
  d.basis = [](const Term& t, const PointContext& pc, BasisOut out) {
    const double a = units::kTwoPi * pc.s[t.axis] / t.period_mm;
    out(t.direction, 0) = std::sin(a);
    out(t.direction, 1) = std::cos(a);
  };
  d.label = [](const Term& t) {
    return fmt::format("cyclic {}→{} ({:.2f} mm)", axis_name(t.axis), axis_name(t.direction),
                       t.period_mm);
  };
  d.description = [](const Term& t) {
    return fmt::format(
        "{} oscillates with {} (period {:.2f}{} mm, {:.2f} µm): ballscrew pitch "
        "error between table points",
        axis_name(t.direction), axis_name(t.axis), t.period_mm,
        t.searched_stderr > 0.0 ? fmt::format(" ± {:.2g}", t.searched_stderr) : std::string(),
        std::hypot(coef_or_zero(t, 0), coef_or_zero(t, 1)));
  };
  d.params = [](const Term& t) -> NamedValues {
    const double s = coef_or_zero(t, 0), c = coef_or_zero(t, 1);
    return {{"amplitude_um", std::hypot(s, c)},
            {"phase_rad", std::atan2(c, s)},
            {"period_mm", t.period_mm}};
  };
  d.param_stderr = [](const Term& t) -> NamedValues {
    auto se = [&](std::size_t i) { return i < t.stderr_.size() ? t.stderr_[i] : 0.0; };
    // Amplitude error ≈ the coefficient errors (sin/cos columns are nearly orthogonal).
    const double amp_se = std::hypot(se(0), se(1)) / std::sqrt(2.0);
    const double amp = std::hypot(coef_or_zero(t, 0), coef_or_zero(t, 1));
    return {{"amplitude_um", amp_se},
            {"phase_rad", amp > 0.0 ? amp_se / amp : 0.0},
            {"period_mm", t.searched_stderr}};
  };
  d.read_fields = [](Term& t, const OverlayFields& in) {
    t.period_mm = in.number("period_mm");
    if (!(t.period_mm > 0.0)) in.fail("period_mm", "period must be positive");
  };
  d.write_fields = [](const Term& t, std::string& y) {
    y += fmt::format("    period_mm: {:.17g}\n", t.period_mm);
  };
  return d;
}

}  // namespace abbe::diagnose::effects
