#pragma once
// ModelSet: the error models of one prediction, evaluated side by side at
// each point (one model, or every model of the table for `--model all`),
// with the running statistics of every model over all points.
#include <Eigen/Core>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "abbe/io/input_error.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/model/error_extension.hpp"
#include "abbe/model/error_model.hpp"
#include "abbe/model/model_kind.hpp"

namespace abbe::pipeline {

// Running statistics of one model's |e| over all points.
struct ModelStats {
  std::size_t points = 0;
  Eigen::Vector3d max_abs_um = Eigen::Vector3d::Zero();
  double sum_d2 = 0.0;        // µm²
  double max_um = 0.0;        // of |e|
  std::size_t max_line = 0;   // source line of the largest |e| (first one)
  std::size_t max_point = 0;  // ordinal of that point (as given to add), to merge groups
  // Inline: it runs once per point and model (in ModelSet, for the point's group).
  void add(const Eigen::Vector3d& e_um, double d_um, std::size_t line, std::size_t point = 0) {
    max_abs_um = max_abs_um.cwiseMax(e_um.cwiseAbs());
    sum_d2 += d_um * d_um;
    if (d_um > max_um || points == 0) {
      max_um = d_um;
      max_line = line;
      max_point = point;
    }
    ++points;
  }
  double rms_um() const;
};

// The statistics of two disjoint groups of points as one, as if their points
// had been added in the order of their ordinals: the largest |e| is the first
// one of both (the lower max_point of equal maxima; |e| is finite). sum_d2 is
// a's plus b's, which is not the sum in point order to the last bit (ModelSet
// keeps that one apart).
ModelStats merged(const ModelStats& a, const ModelStats& b);

class ModelSet {
 public:
  // `extension`: an extra deviation every model carries (null: none).
  ModelSet(const machine::Machine& machine, std::vector<model::ModelKind> kinds,
           std::shared_ptr<const model::ErrorExtension> extension = nullptr);

  // Evaluates every model at `point` and updates the statistics. A model's
  // abbe::InputError (a lookup outside a table under the policy `error`) is
  // re-thrown at `file`:`line`, naming the point.
  // `rapid`: the point lies on a rapid (else on a cutting move, or it is a
  // point of a CSV); counted in rapid_stats() or cutting_stats() as well.
  // Inline: it runs once per point, and the models' calls are opaque.
  void evaluate(const model::EvalPoint& point, const std::string& file, std::size_t line,
                bool rapid = false) {
    const std::size_t n = models_.size();
    model::Deviation* const devs = deviations_.data();
    for (std::size_t i = 0; i < n; ++i) {
      try {
        devs[i] = models_[i].evaluate(point, data_[i]);
      } catch (const InputError& e) {
        rethrow_at(e, point, file, line);
      }
    }
    // The point goes into its group's statistics only; those of all points
    // are merged from the groups when asked for (stats()), but for the sum of
    // |e|², kept here in point order so that the RMS is the same number.
    ModelStats* const group = (rapid ? rapid_ : cutting_).data();
    double* const sum_d2 = sum_d2_.data();
    for (std::size_t i = 0; i < n; ++i) {
      const double norm = devs[i].e_um.norm();
      norms_[i] = norm;
      group[i].add(devs[i].e_um, norm, line, points_);
      sum_d2[i] += norm * norm;
    }
    ++points_;
  }

  std::size_t size() const { return kinds_.size(); }
  const std::vector<model::ModelKind>& kinds() const { return kinds_; }
  // Of the last evaluated point, per model:
  const std::vector<model::Deviation>& deviations() const { return deviations_; }
  const std::vector<double>& norms_um() const { return norms_; }  // |e|
  // Over all points, per model:
  std::vector<ModelStats> stats() const;  // all points (merged from the two groups)
  const std::vector<ModelStats>& cutting_stats() const { return cutting_; }
  const std::vector<ModelStats>& rapid_stats() const { return rapid_; }
  std::size_t out_of_range_lookups(std::size_t model) const;
  std::size_t points() const { return points_; }

 private:
  // A model's error at `file`:`line`, naming the point.
  [[noreturn]] static void rethrow_at(const InputError& e, const model::EvalPoint& point,
                                      const std::string& file, std::size_t line);

  std::vector<model::ModelKind> kinds_;
  std::vector<model::ErrorModel> models_;
  std::vector<model::ModelData> data_;
  std::vector<model::Deviation> deviations_;
  std::vector<double> norms_;
  std::vector<ModelStats> cutting_, rapid_;
  std::vector<double> sum_d2_;  // of all points, in point order
  std::size_t points_ = 0;
};

}  // namespace abbe::pipeline
