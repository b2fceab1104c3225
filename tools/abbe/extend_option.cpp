#include "extend_option.hpp"

#include <spdlog/spdlog.h>

#include "abbe/diagnose/overlay_extension.hpp"

namespace abbe::cli {

model::ErrorModel extend_with_overlay(const model::ErrorModel& model,
                                      const machine::Machine& machine,
                                      const std::string& overlay_file, double extend_time_s) {
  const model::ErrorModel extended =
      diagnose::extend_model(model, machine, overlay_file, extend_time_s);
  const auto* ext = dynamic_cast<const diagnose::OverlayExtension*>(extended.extension());
  if (ext && ext->base() != model.kind())
    spdlog::warn("{}: the overlay was fitted on the {} model, it is added to {}", overlay_file,
                 model::to_string(ext->base()), model::to_string(model.kind()));
  if (ext && ext->time_dependent())
    spdlog::info("{}: time-dependent terms evaluated at campaign time {} s (--extend-time)",
                 overlay_file, extend_time_s);
  return extended;
}

}  // namespace abbe::cli
