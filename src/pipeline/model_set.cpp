#include "abbe/pipeline/model_set.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace abbe::pipeline {

double ModelStats::rms_um() const {
  return points ? std::sqrt(sum_d2 / static_cast<double>(points)) : 0.0;
}

ModelStats merged(const ModelStats& a, const ModelStats& b) {
  if (b.points == 0) return a;
  if (a.points == 0) return b;
  const bool b_max = b.max_um > a.max_um || (b.max_um == a.max_um && b.max_point < a.max_point);
  ModelStats m = b_max ? b : a;
  m.points = a.points + b.points;
  m.max_abs_um = a.max_abs_um.cwiseMax(b.max_abs_um);
  m.sum_d2 = a.sum_d2 + b.sum_d2;
  return m;
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
  cutting_.resize(kinds_.size());
  rapid_.resize(kinds_.size());
  sum_d2_.assign(kinds_.size(), 0.0);
}

std::vector<ModelStats> ModelSet::stats() const {
  std::vector<ModelStats> all(kinds_.size());
  for (std::size_t i = 0; i < all.size(); ++i) {
    all[i] = merged(cutting_[i], rapid_[i]);
    all[i].sum_d2 = sum_d2_[i];
  }
  return all;
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
