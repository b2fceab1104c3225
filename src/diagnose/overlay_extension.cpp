#include "abbe/diagnose/overlay_extension.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "abbe/io/input_error.hpp"

namespace abbe::diagnose {
namespace {

model::ModelKind kind_of(const Overlay& overlay) {
  // Overlay::parse accepts only the model table's names.
  return model::parse_model_kind(overlay.base_model).value_or(model::ModelKind::ae_arm);
}

// a = max(a, v), thread-safe.
void raise_to(std::atomic<double>& a, double v) {
  double cur = a.load();
  while (v > cur && !a.compare_exchange_weak(cur, v)) {
  }
}

}  // namespace

OverlayExtension::OverlayExtension(Overlay overlay, const machine::Machine& machine,
                                   std::optional<double> fixed_time_s)
    : overlay_(std::move(overlay)),
      fixed_time_s_(fixed_time_s),
      base_(machine, kind_of(overlay_)),
      other_(machine, model::alternative_model(kind_of(overlay_))) {
  with_time_ = overlay_.time_dependent();
  needs_models_ = std::any_of(overlay_.terms.begin(), overlay_.terms.end(),
                              [](const Term& t) { return t.kind == TermKind::model_choice; });
}

std::string OverlayExtension::domain_warning(std::size_t per_point) const {
  const std::string name = overlay_.file.empty() ? "the overlay" : overlay_.file;
  if (overlay_.terms.empty()) return "";
  if (!overlay_.domain.known)
    return fmt::format(
        "{}: the overlay records no domain (written before abbe recorded the box and time "
        "window of the fit): its domain is unknown, every term is evaluated as written, also "
        "where it extrapolates; run `abbe diagnose --overlay` again to record it",
        name);
  const std::size_t n = outside_.load() / std::max<std::size_t>(per_point, 1);
  if (n == 0) return "";
  const std::size_t total = evaluations_.load() / std::max<std::size_t>(per_point, 1);
  std::string beyond;
  if (box_excess_mm_.load() > 0.0)
    beyond = fmt::format("up to {:.4g} mm beyond the box", box_excess_mm_.load());
  if (with_time_ && time_excess_s_.load() > 0.0)
    beyond += fmt::format("{} {:.4g} s outside the time window", beyond.empty() ? "up to" : ",",
                          time_excess_s_.load());
  return fmt::format(
      "{}: {} of {} {} outside the domain the overlay was fitted on ({}; {}): its polynomial, "
      "smooth and time terms are held at their value on the boundary there (not extrapolated), "
      "its linear and periodic terms are evaluated as written",
      name, n, total, per_point == 0 ? "evaluations" : "points", overlay_.domain.text(with_time_),
      beyond);
}

PointContext OverlayExtension::context(const model::EvalPoint& point,
                                       const model::ModelData& data) const {
  PointContext pc;
  pc.p = point.p;
  pc.s = point.p + Eigen::Vector3d(0.0, 0.0, point.tool_length);
  pc.t = fixed_time_s_ ? *fixed_time_s_ : point.time;
  for (std::size_t k = 0; k < 3; ++k) pc.dir[k] = point.dir[k];
  // The component tables are the same for every model kind: ε_j is the
  // lookup the extended model has just made.
  for (std::size_t j = 0; j < 3; ++j) pc.eps_urad[j] = data.errors[j].theta_urad;
  if (needs_models_) {
    model::ModelData a, b;  // fresh workspaces keep this const and thread-safe
    pc.model_delta_um = other_.evaluate(point, b).e_um - base_.evaluate(point, a).e_um;
  }
  return pc;
}

Eigen::Vector3d OverlayExtension::extra_um(const model::EvalPoint& point, const model::Deviation&,
                                           const model::ModelData& data) const {
  const PointContext pc = context(point, data);
  ++evaluations_;
  if (!overlay_.domain.contains(pc, with_time_)) {
    ++outside_;
    raise_to(box_excess_mm_, overlay_.domain.box_excess(pc).maxCoeff());
    if (with_time_) raise_to(time_excess_s_, overlay_.domain.time_excess(pc));
  }
  const Eigen::Vector3d e = overlay_.evaluate(pc);
  if (!e.allFinite() || e.norm() > kOverlayLimitUm)
    throw InputError(
        {overlay_.file.empty() ? "<overlay>" : overlay_.file, 0, 0, "", ""},
        fmt::format("the overlay adds {:.4g} µm at s = ({:.4f}, {:.4f}, {:.4f}) mm, t = {:.6g} s: "
                    "beyond the {:g} µm an overlay may correct, refused (a broken overlay, or "
                    "terms far outside the data they were fitted on; domain: {})",
                    e.norm(), pc.s.x(), pc.s.y(), pc.s.z(), pc.t, kOverlayLimitUm,
                    overlay_.domain.text(true)));
  return e;
}

model::ErrorModel extend_model(const model::ErrorModel& model, const machine::Machine& machine,
                               const std::string& overlay_file,
                               std::optional<double> fixed_time_s) {
  return model.with_extension(
      std::make_shared<const OverlayExtension>(Overlay::load(overlay_file), machine, fixed_time_s));
}

}  // namespace abbe::diagnose
