#include "abbe/pipeline/predict.hpp"

#include "abbe/machine/travel_check.hpp"
#include "abbe/pipeline/interpreter_setup.hpp"
#include "abbe/pipeline/point_reader.hpp"

namespace abbe::pipeline {
namespace {

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

PredictInput predict_input_of(const std::string& file, bool force_points) {
  return force_points || ends_with(file, ".csv") || ends_with(file, ".CSV") ? PredictInput::points
                                                                            : PredictInput::program;
}

PredictionSummary predict(std::istream& in, const std::string& file,
                          const machine::Machine& machine, const PredictOptions& options,
                          const PredictionSink& sink) {
  ModelSet models(machine, options.models, options.extension);
  machine::TravelCheck travel(machine.spec().travel);
  auto evaluate = [&](const model::EvalPoint& p, std::size_t line, bool rapid) {
    travel.add(p.p, p.tool_length, line);
    models.evaluate(p, file, line, rapid);
    if (sink) sink(p, line, models);
  };
  if (options.input == PredictInput::points) {
    PointReader reader(in, file, machine.tool_length());
    model::EvalPoint p;
    std::size_t line = 0;
    while (reader.next(p, line)) evaluate(p, line, false);
  } else {
    run_path(in, file, options.config ? *options.config : interpreter_config(machine), options.path,
             [&](const path::PathPoint& pp) {
               evaluate(eval_point(pp), pp.line, pp.kind == gcode::MotionKind::rapid);
             });
  }
  PredictionSummary summary = summarize(models, machine, file);
  summary.moves = options.input == PredictInput::program;
  summary.outside_travel_points = travel.outside();
  summary.outside_travel_per_axis = travel.outside_per_axis();
  summary.travel_text = travel.text();
  return summary;
}

}  // namespace abbe::pipeline
