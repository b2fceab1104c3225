#pragma once
// --extend OVERLAY.yaml [--extend-time S] of compensate and verify: the
// model extended by the overlay (diagnose/overlay_extension.hpp), with a
// warning when the overlay was fitted on another model and a note when its
// time-dependent terms are evaluated at the fixed campaign time.
#include <string>

#include "abbe/machine/machine.hpp"
#include "abbe/model/error_model.hpp"

namespace abbe::cli {

model::ErrorModel extend_with_overlay(const model::ErrorModel& model,
                                      const machine::Machine& machine,
                                      const std::string& overlay_file, double extend_time_s);

}  // namespace abbe::cli
