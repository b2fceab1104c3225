#pragma once
// The model options of compensate and verify: --machine, --model and
// --extend OVERLAY.yaml [--extend-time S]. make_model builds the error model,
// extended by the overlay (diagnose/overlay_extension.hpp) when one is given,
// with a warning when the overlay was fitted on another model and a note when
// its time-dependent terms are evaluated at the fixed campaign time.
#include <CLI/CLI.hpp>
#include <string>

#include "abbe/machine/machine.hpp"
#include "abbe/model/error_extension.hpp"
#include "abbe/model/error_model.hpp"

namespace abbe::cli {

struct ModelOptions {
  std::string machine;
  std::string model = "ae-arm";
  std::string extend;        // overlay of effects found by `abbe diagnose` (docs/compensation.md)
  double extend_time = 0.0;  // campaign time (s) for time-dependent overlay terms
};

// What --extend does outside the overlay's domain (appended to its help).
inline constexpr const char* kOverlayDomainHelp =
    ". Outside the box and time window the overlay was fitted on, its polynomial, smooth and "
    "time terms are held at their boundary value (clamped, never extrapolated; a warning counts "
    "the points); an overlay correction beyond 1 mm or not finite is refused (exit 1)";

// `extend_help` says what the command does with the extended model.
void add_model_options(CLI::App& sub, ModelOptions& o, const char* extend_help);

// Throws abbe::InputError for an unknown model name or a bad overlay file.
model::ErrorModel make_model(const ModelOptions& o, const machine::Machine& machine);

// After a run with an overlay (`ext` an OverlayExtension, else nothing is
// done): warns once when points lay outside the overlay's domain, or when the
// overlay records none. `per_point`: evaluations of the extension per point
// (0: unknown, the warning counts evaluations).
void warn_overlay_domain(const model::ErrorExtension* ext, std::size_t per_point = 0);

}  // namespace abbe::cli
