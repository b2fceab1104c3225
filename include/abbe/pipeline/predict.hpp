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
#include "abbe/machine/travel_check.hpp"
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

// `sink`: callable as sink(point, line, models) like a PredictionSink; a
// template so that a lambda (the CLI's writer, a Python callback's
// collector) is inlined into the point loop of a program.
// Throws abbe::InputError on bad input (file, line, column).
template <class Sink>
PredictionSummary predict(std::istream& in, const std::string& file,
                          const machine::Machine& machine, const PredictOptions& options,
                          Sink&& sink);

namespace detail {

// The state of one predict() run: the models with their statistics and the
// travel check, fed one point at a time (inline: it runs once per point).
class PredictRun {
 public:
  PredictRun(const machine::Machine& machine, const PredictOptions& options,
             const std::string& file);

  void evaluate(const model::EvalPoint& p, std::size_t line, bool rapid) {
    travel_.add(p.p, p.tool_length, line);
    models_.evaluate(p, file_, line, rapid);
  }
  const ModelSet& models() const { return models_; }
  // The interpreter's setup: the options' or the machine file's.
  gcode::InterpreterConfig config(const PredictOptions& options) const;
  // A CSV of points (PointReader): each point evaluated, then handed to `each`.
  void read_points(std::istream& in,
                   const std::function<void(const model::EvalPoint&, std::size_t)>& each);
  PredictionSummary summary(bool moves) const;

 private:
  const machine::Machine& machine_;
  const std::string& file_;
  ModelSet models_;
  machine::TravelCheck travel_;
};

}  // namespace detail

template <class Sink>
PredictionSummary predict(std::istream& in, const std::string& file,
                          const machine::Machine& machine, const PredictOptions& options,
                          Sink&& sink) {
  detail::PredictRun run(machine, options, file);
  if (options.input == PredictInput::points) {
    run.read_points(
        in, [&](const model::EvalPoint& p, std::size_t line) { sink(p, line, run.models()); });
  } else {
    run_path(in, file, run.config(options), options.path, [&](const path::PathPoint& pp) {
      const model::EvalPoint p = eval_point(pp);
      run.evaluate(p, pp.line, pp.kind == gcode::MotionKind::rapid);
      sink(p, pp.line, run.models());
    });
  }
  return run.summary(options.input == PredictInput::program);
}

}  // namespace abbe::pipeline
