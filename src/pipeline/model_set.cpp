#include "abbe/pipeline/model_set.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace abbe::pipeline {

double ModelStats::rms_um() const {
  return points ? std::sqrt(sum_d2 / static_cast<double>(points)) : 0.0;
}

ModelSet::ModelSet(const machine::Machine& machine, std::vector<model::ModelKind> kinds,
                   std::shared_ptr<const model::ErrorExtension> extension)
    : kinds_(std::move(kinds)) {
  // The tables are resampled once, for the first model; the others share them.
  for (auto k : kinds_) {
    models_.push_back(models_.empty() ? model::ErrorModel(machine, k) : models_.front().as_kind(k));
    if (extension) models_.back() = models_.back().with_extension(extension);
  }
  data_.resize(kinds_.size());
  deviations_.resize(kinds_.size());
  norms_.resize(kinds_.size());
  stats_.resize(kinds_.size());
  cutting_.resize(kinds_.size());
  rapid_.resize(kinds_.size());
}

void ModelSet::rethrow_at(const InputError& e, const model::EvalPoint& point,
                          const std::string& file, std::size_t line) {
  throw InputError({file, line, 0, e.where().field, ""},
                   fmt::format("at the point ({:.4f}, {:.4f}, {:.4f}) mm: {}", point.p.x(),
                               point.p.y(), point.p.z(), e.message()));
}

std::size_t ModelSet::out_of_range_lookups(std::size_t model) const {
  return data_.at(model).out_of_range_lookups;
}

}  // namespace abbe::pipeline
