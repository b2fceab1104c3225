#include "abbe/pipeline/prediction_summary.hpp"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

namespace abbe::pipeline {

PredictionSummary summarize(const ModelSet& models, const machine::Machine& machine,
                            const std::string& input) {
  PredictionSummary s;
  s.machine = machine.name();
  s.input = input;
  s.points = models.points();
  s.out_of_range = machine.out_of_range();
  for (std::size_t i = 0; i < models.size(); ++i)
    s.models.push_back({models.kinds()[i], models.stats()[i], models.out_of_range_lookups(i)});
  return s;
}

std::string summary_json(const PredictionSummary& s) {
  nlohmann::json j;
  j["machine"] = s.machine;
  j["input"] = s.input;
  j["points"] = s.points;
  j["out_of_range_policy"] = machine::to_string(s.out_of_range);
  j["models"] = nlohmann::json::array();
  for (const ModelSummary& m : s.models)
    j["models"].push_back({{"model", model::to_string(m.kind)},
                           {"points", m.stats.points},
                           {"max_abs_dx_um", m.stats.max_abs_um.x()},
                           {"max_abs_dy_um", m.stats.max_abs_um.y()},
                           {"max_abs_dz_um", m.stats.max_abs_um.z()},
                           {"rms_d_um", m.stats.rms_um()},
                           {"max_d_um", m.stats.max_um},
                           {"out_of_range_lookups", m.out_of_range_lookups}});
  return j.dump(2);
}

std::string summary_table(const PredictionSummary& s) {
  std::string text = fmt::format("{}: {} points, machine \"{}\"\n", s.input, s.points, s.machine);
  text += fmt::format(
      "  {:<7} {:>10} {:>10} {:>10} {:>10} {:>10} {:>12}\n", "model", "max|dx| µm", "max|dy| µm",
      "max|dz| µm", "rms|d| µm", "max|d| µm",
      s.out_of_range == machine::OutOfRangePolicy::extrapolate ? "extrapolated" : "clamped");
  for (const ModelSummary& m : s.models)
    text += fmt::format("  {:<7} {:>10.4f} {:>10.4f} {:>10.4f} {:>10.4f} {:>10.4f} {:>12}\n",
                        model::to_string(m.kind), m.stats.max_abs_um.x(), m.stats.max_abs_um.y(),
                        m.stats.max_abs_um.z(), m.stats.rms_um(), m.stats.max_um,
                        m.out_of_range_lookups);
  return text;
}

}  // namespace abbe::pipeline
