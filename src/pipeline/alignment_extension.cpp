#include "abbe/pipeline/alignment_extension.hpp"

namespace abbe::pipeline {

Eigen::Vector3d AlignmentExtension::extra_um(const model::EvalPoint& point,
                                             const model::Deviation& base,
                                             const model::ModelData&) const {
  return aligned_deviation_um(motion_, point.p, base.e_um) - base.e_um;
}

ModelAlignment program_setup(std::istream& program, const std::string& file,
                             const machine::Machine& machine, model::ModelKind model,
                             const PathOptions& path, const AlignOptions& align) {
  PredictOptions po;
  po.models = {model};
  po.input = PredictInput::program;
  po.path = path;
  return predict_aligned(program, file, machine, po, align, nullptr, nullptr)
      .alignment.models.at(0);
}

}  // namespace abbe::pipeline
