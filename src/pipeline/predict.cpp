#include "abbe/pipeline/predict.hpp"

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

namespace detail {

PredictRun::PredictRun(const machine::Machine& machine, const PredictOptions& options,
                       const std::string& file)
    : machine_(machine),
      file_(file),
      models_(machine, options.models, options.extension),
      travel_(machine.spec().travel) {}

gcode::InterpreterConfig PredictRun::config(const PredictOptions& options) const {
  return options.config ? *options.config : interpreter_config(machine_);
}

void PredictRun::read_points(
    std::istream& in, const std::function<void(const model::EvalPoint&, std::size_t)>& each) {
  PointReader reader(in, file_, machine_.tool_length());
  model::EvalPoint p;
  std::size_t line = 0;
  while (reader.next(p, line)) {
    evaluate(p, line, false);
    each(p, line);
  }
}

PredictionSummary PredictRun::summary(bool moves) const {
  PredictionSummary summary = summarize(models_, machine_, file_);
  summary.moves = moves;
  summary.outside_travel_points = travel_.outside();
  summary.outside_travel_per_axis = travel_.outside_per_axis();
  summary.travel_text = travel_.text();
  return summary;
}

}  // namespace detail
}  // namespace abbe::pipeline
