#pragma once
// Overlay: the effects a diagnosis found, as extra deviation terms on top of
// an error model ("extended model"). Written and read as YAML (schema in
// docs/formats.md, "Machine overlay"); `predict`, `diagnose` and
// `compensate` accept it with `--extend OVERLAY.yaml`.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "abbe/diagnose/term.hpp"

namespace abbe::diagnose {

class Overlay {
 public:
  std::string base_model = "ae-arm";  // the model the overlay was fitted on top of
  std::string machine;                // the machine name it was fitted for (informative)
  std::vector<Term> terms;

  // Extra deviation of the tool tip, µm (the sum of every term).
  Eigen::Vector3d evaluate(const PointContext& pc) const;

  // Throws abbe::InputError naming the file, line and field.
  static Overlay parse(const std::string& yaml_text, const std::string& file);
  static Overlay load(const std::string& path);
  std::string to_yaml() const;
};

}  // namespace abbe::diagnose
