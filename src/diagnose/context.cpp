#include "abbe/diagnose/context.hpp"

namespace abbe::diagnose {

ContextBuilder::ContextBuilder(const machine::Machine& machine, model::ModelKind base)
    : base_(machine, base), other_(machine, model::alternative_model(base)) {}

PointContext ContextBuilder::make(const model::EvalPoint& point, const std::string& set,
                                  Eigen::Vector3d& predicted_um) {
  PointContext pc;
  pc.p = point.p;
  pc.s = point.p + Eigen::Vector3d(0.0, 0.0, point.tool_length);
  pc.t = point.time;
  for (std::size_t k = 0; k < 3; ++k) pc.dir[k] = point.dir[k];
  pc.set = set;
  predicted_um = base_.evaluate(point, base_data_).e_um;
  for (std::size_t j = 0; j < 3; ++j) pc.eps_urad[j] = base_data_.errors[j].theta_urad;
  pc.model_delta_um = other_.evaluate(point, other_data_).e_um - predicted_um;
  return pc;
}

}  // namespace abbe::diagnose
