// model_choice: the residual is the difference to another error model
// (weight 1: the other model is right).
#include <fmt/format.h>

#include "builtin_effects.hpp"

namespace abbe::diagnose::effects {

EffectDescriptor model_choice() {
  EffectDescriptor d = make_descriptor(TermKind::model_choice, "model_choice", "model_choice");
  d.extrapolates = true;  // a share of the other model, wherever it is
  d.reads_axis = d.writes_axis = d.reads_direction = false;
  d.basis = [](const Term&, const PointContext& pc, BasisOut out) {
    out.col(0) = pc.model_delta_um;
  };
  d.label = [](const Term& t) { return fmt::format("model_choice ({})", t.other_model); };
  d.description = [](const Term& t) {
    return fmt::format(
        "the residual is the difference to the {} model (weight {:.2f}): angular errors are "
        "counted with the wrong arms (Abbe double counting)",
        t.other_model, coef_or_zero(t, 0));
  };
  d.params = [](const Term& t) -> NamedValues { return {{"weight", coef_or_zero(t, 0)}}; };
  d.read_fields = [](Term& t, const OverlayFields& in) { t.other_model = in.text("other_model"); };
  d.write_fields = [](const Term& t, std::string& y) {
    y += fmt::format("    other_model: {}\n", t.other_model);
  };
  return d;
}

}  // namespace abbe::diagnose::effects
