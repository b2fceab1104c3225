#pragma once
// Overlay: the effects a diagnosis found, as extra deviation terms on top of
// an error model ("extended model"). Written and read as YAML (schema in
// docs/formats.md, "Machine overlay"); `predict`, `diagnose` and
// `compensate` accept it with `--extend OVERLAY.yaml`.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "abbe/diagnose/overlay_domain.hpp"
#include "abbe/diagnose/term.hpp"

namespace abbe::diagnose {

class Overlay {
 public:
  std::string base_model = "ae-arm";  // the model the overlay was fitted on top of
  std::string machine;                // the machine name it was fitted for (informative)
  std::vector<Term> terms;
  // The box and time window the terms were fitted on (`domain:`; unknown in
  // overlays written before it was recorded).
  OverlayDomain domain;
  std::string file;  // where it was read from (messages); empty when built in memory

  // Extra deviation of the tool tip, µm (the sum of every term). A term whose
  // kind does not extrapolate is evaluated at the point clamped into the
  // domain (overlay_domain.hpp); inside the domain nothing is clamped.
  Eigen::Vector3d evaluate(const PointContext& pc) const;
  // True if a term depends on the time t.
  bool time_dependent() const;

  // Throws abbe::InputError naming the file, line and field.
  static Overlay parse(const std::string& yaml_text, const std::string& file);
  static Overlay load(const std::string& path);
  std::string to_yaml() const;
};

}  // namespace abbe::diagnose
