#pragma once
// StoredPrediction: a prediction (`predict`) with every point kept, and the
// models' deviations there, for the outputs that need all points before they
// write any: the part's set-up of `predict --align` and the Monte Carlo draws
// of `predict --uncertainty`.
#include <cstddef>
#include <functional>
#include <istream>
#include <string>
#include <vector>

#include "abbe/machine/machine.hpp"
#include "abbe/model/error_model.hpp"
#include "abbe/pipeline/model_set.hpp"
#include "abbe/pipeline/predict.hpp"
#include "abbe/pipeline/prediction_summary.hpp"

namespace abbe::pipeline {

struct StoredPrediction {
  PredictionSummary summary;
  std::vector<model::EvalPoint> points;
  std::vector<std::size_t> lines;
  std::vector<bool> rapid;  // on a rapid (else on a feed motion, or a CSV point)
  std::vector<std::vector<model::Deviation>> devs;  // [model][point]
  std::vector<std::vector<double>> norms;           // [model][point], |e| µm

  std::size_t size() const { return points.size(); }

  // Every point in order with the models' deviations and |e| there.
  using Row = std::function<void(std::size_t i, const std::vector<model::Deviation>& devs,
                                 const std::vector<double>& norms_um)>;
  void for_each(const Row& row) const;
};

// `predict`, keeping every point. `progress` is predict's sink (may be empty).
StoredPrediction predict_stored(std::istream& in, const std::string& file,
                                const machine::Machine& machine, const PredictOptions& options,
                                const PredictionSink& progress);

}  // namespace abbe::pipeline
