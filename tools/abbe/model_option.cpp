#include "model_option.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "abbe/diagnose/overlay_extension.hpp"
#include "abbe/io/input_error.hpp"

namespace abbe::cli {

void add_model_options(CLI::App& sub, ModelOptions& o, const char* extend_help) {
  sub.add_option("--machine", o.machine, "Machine file (YAML, docs/formats.md)")->required();
  sub.add_option("--model", o.model, "Error model: " + model::model_names_text(false))
      ->check(CLI::IsMember(model::model_names(false)))
      ->capture_default_str();
  sub.add_option("--extend", o.extend, std::string(extend_help) + kOverlayDomainHelp);
  sub.add_option("--extend-time", o.extend_time,
                 "Campaign time (s) at which time-dependent overlay terms are evaluated (held "
                 "inside the overlay's time window)")
      ->capture_default_str();
}

model::ErrorModel make_model(const ModelOptions& o, const machine::Machine& machine) {
  const auto kind = model::parse_model_kind(o.model);
  if (!kind)
    throw InputError(
        {"<command line>", 0, 0, "--model", ""},
        fmt::format("unknown model \"{}\" ({})", o.model, model::model_names_text(false)));
  const model::ErrorModel base(machine, *kind);
  if (o.extend.empty()) return base;
  const model::ErrorModel extended = diagnose::extend_model(base, machine, o.extend, o.extend_time);
  const auto* ext = dynamic_cast<const diagnose::OverlayExtension*>(extended.extension());
  if (ext && ext->base() != base.kind())
    spdlog::warn("{}: the overlay was fitted on the {} model, it is added to {}", o.extend,
                 model::to_string(ext->base()), model::to_string(base.kind()));
  if (ext && ext->time_dependent())
    spdlog::info("{}: time-dependent terms evaluated at campaign time {} s (--extend-time)",
                 o.extend, o.extend_time);
  return extended;
}

void warn_overlay_domain(const model::ErrorExtension* ext, std::size_t per_point) {
  const auto* overlay = dynamic_cast<const diagnose::OverlayExtension*>(ext);
  if (!overlay) return;
  const std::string w = overlay->domain_warning(per_point);
  if (!w.empty()) spdlog::warn("{}", w);
}

}  // namespace abbe::cli
