#pragma once
// AlignmentExtension: turns a model's prediction e into the deviation that
// remains after the part's set-up, T(P + e) − P (part_alignment.hpp), so that
// a consumer of the model — `abbe compensate --align` — corrects only what
// the set-up does not remove (docs/compensation.md, "Only what the set-up
// leaves").
#include <Eigen/Core>
#include <istream>
#include <string>

#include "abbe/machine/machine.hpp"
#include "abbe/model/error_extension.hpp"
#include "abbe/model/error_model.hpp"
#include "abbe/pipeline/aligned_prediction.hpp"
#include "abbe/pipeline/part_alignment.hpp"
#include "abbe/pipeline/program_path.hpp"

namespace abbe::pipeline {

class AlignmentExtension : public model::ErrorExtension {
 public:
  explicit AlignmentExtension(RigidMotion motion) : motion_(motion) {}
  Eigen::Vector3d extra_um(const model::EvalPoint& point, const model::Deviation& base,
                           const model::ModelData& data) const override;
  const RigidMotion& motion() const { return motion_; }

 private:
  RigidMotion motion_;
};

// The set-up of the part a program cuts, predicted with `model` (no
// extension): the program is predicted once and aligned (best fit or
// datums). Returns the alignment summary of that model.
ModelAlignment program_setup(std::istream& program, const std::string& file,
                             const machine::Machine& machine, model::ModelKind model,
                             const PathOptions& path, const AlignOptions& align);

}  // namespace abbe::pipeline
