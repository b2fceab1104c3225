#pragma once
// predict: the whole of `abbe predict` as one library call — an NC program
// (through run_path) or a CSV of points (PointReader) evaluated by a set of
// error models, every point handed to a sink (PredictionWriter, a Python
// callback, …), returning the summary.
#include <functional>
#include <istream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "abbe/machine/machine.hpp"
#include "abbe/model/error_extension.hpp"
#include "abbe/model/model_kind.hpp"
#include "abbe/pipeline/model_set.hpp"
#include "abbe/pipeline/prediction_summary.hpp"
#include "abbe/pipeline/program_path.hpp"

namespace abbe::pipeline {

enum class PredictInput { program, points };

// "points" for a name ending in .csv or .CSV (or when `force_points`),
// "program" otherwise.
PredictInput predict_input_of(const std::string& file, bool force_points);

struct PredictOptions {
  std::vector<model::ModelKind> models{model::ModelKind::ae_arm};
  PredictInput input = PredictInput::program;
  PathOptions path;                                        // programs only
  std::shared_ptr<const model::ErrorExtension> extension;  // null: none
  // The interpreter's setup; empty: the machine file's (interpreter_config).
  std::optional<gcode::InterpreterConfig> config;
};

// Called at every point after the models are evaluated (models.deviations()).
using PredictionSink =
    std::function<void(const model::EvalPoint& point, std::size_t line, const ModelSet& models)>;

// Throws abbe::InputError on bad input (file, line, column).
PredictionSummary predict(std::istream& in, const std::string& file,
                          const machine::Machine& machine, const PredictOptions& options,
                          const PredictionSink& sink);

}  // namespace abbe::pipeline
