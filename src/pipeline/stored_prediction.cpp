#include "abbe/pipeline/stored_prediction.hpp"

namespace abbe::pipeline {

void StoredPrediction::for_each(const Row& row) const {
  std::vector<model::Deviation> row_devs(devs.size());
  std::vector<double> row_norms(devs.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (std::size_t m = 0; m < devs.size(); ++m) {
      row_devs[m] = devs[m][i];
      row_norms[m] = norms[m][i];
    }
    row(i, row_devs, row_norms);
  }
}

StoredPrediction predict_stored(std::istream& in, const std::string& file,
                                const machine::Machine& machine, const PredictOptions& options,
                                const PredictionSink& progress) {
  StoredPrediction s;
  s.devs.resize(options.models.size());
  s.norms.resize(options.models.size());
  std::size_t rapid_before = 0;
  s.summary = predict(in, file, machine, options,
                      [&](const model::EvalPoint& p, std::size_t line, const ModelSet& models) {
                        // A rapid point is the one the rapid statistics counted.
                        const std::size_t rapid_now = models.rapid_stats().front().points;
                        s.points.push_back(p);
                        s.lines.push_back(line);
                        s.rapid.push_back(rapid_now != rapid_before);
                        rapid_before = rapid_now;
                        for (std::size_t m = 0; m < models.size(); ++m) {
                          s.devs[m].push_back(models.deviations()[m]);
                          s.norms[m].push_back(models.norms_um()[m]);
                        }
                        if (progress) progress(p, line, models);
                      });
  return s;
}

}  // namespace abbe::pipeline
