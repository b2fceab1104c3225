#include "abbe/pipeline/prediction_summary.hpp"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

namespace abbe::pipeline {
namespace {

nlohmann::json stats_json(const ModelStats& s) {
  return {{"points", s.points},
          {"max_abs_dx_um", s.max_abs_um.x()},
          {"max_abs_dy_um", s.max_abs_um.y()},
          {"max_abs_dz_um", s.max_abs_um.z()},
          {"rms_d_um", s.rms_um()},
          {"max_d_um", s.max_um},
          {"max_line", s.max_line}};
}

std::string stats_cells(const std::string& model, const char* moves, const ModelStats& s,
                        const std::string& lookups) {
  if (s.points == 0)
    return fmt::format("  {:<7} {:<8} {:>8} {:>10} {:>10} {:>10} {:>10} {:>10} {:>8} {:>12}", model,
                       moves, 0, "-", "-", "-", "-", "-", "-", lookups);
  return fmt::format(
      "  {:<7} {:<8} {:>8} {:>10.4f} {:>10.4f} {:>10.4f} {:>10.4f} {:>10.4f} {:>8} {:>12}", model,
      moves, s.points, s.max_abs_um.x(), s.max_abs_um.y(), s.max_abs_um.z(), s.rms_um(), s.max_um,
      s.max_line, lookups);
}

std::string stats_row(const std::string& model, const char* moves, const ModelStats& s,
                      const std::string& lookups) {
  std::string row = stats_cells(model, moves, s, lookups);
  while (!row.empty() && row.back() == ' ') row.pop_back();
  return row + "\n";
}

}  // namespace

PredictionSummary summarize(const ModelSet& models, const machine::Machine& machine,
                            const std::string& input) {
  PredictionSummary s;
  s.machine = machine.name();
  s.input = input;
  s.points = models.points();
  s.out_of_range = machine.out_of_range();
  for (std::size_t i = 0; i < models.size(); ++i)
    s.models.push_back({models.kinds()[i], models.stats()[i], models.cutting_stats()[i],
                        models.rapid_stats()[i], models.out_of_range_lookups(i)});
  s.conventions = machine::analyse_conventions(machine);
  return s;
}

std::string summary_json(const PredictionSummary& s) {
  nlohmann::json j;
  j["machine"] = s.machine;
  j["input"] = s.input;
  j["points"] = s.points;
  j["out_of_range_policy"] = machine::to_string(s.out_of_range);
  j["models"] = nlohmann::json::array();
  for (const ModelSummary& m : s.models) {
    nlohmann::json o = stats_json(m.stats);
    o["model"] = model::to_string(m.kind);
    o["out_of_range_lookups"] = m.out_of_range_lookups;
    if (s.moves) {
      o["cutting"] = stats_json(m.cutting);
      o["rapid"] = stats_json(m.rapid);
    }
    j["models"].push_back(o);
  }
  if (s.conventions.any)
    j["conventions"] = {{"absolute_determined", false},
                        {"aligned_determined", s.conventions.aligned_determined},
                        {"notes", s.conventions.notes}};
  return j.dump(2);
}

std::string summary_table(const PredictionSummary& s) {
  std::string text = fmt::format("{}: {} points, machine \"{}\"\n", s.input, s.points, s.machine);
  text += fmt::format(
      "  {:<7} {:<8} {:>8} {:>10} {:>10} {:>10} {:>10} {:>10} {:>8} {:>12}\n", "model", "moves",
      "points", "max|dx| µm", "max|dy| µm", "max|dz| µm", "rms|d| µm", "max|d| µm", "at line",
      s.out_of_range == machine::OutOfRangePolicy::extrapolate ? "extrapolated" : "clamped");
  for (const ModelSummary& m : s.models) {
    const std::string name = model::to_string(m.kind);
    if (s.moves) {
      text += stats_row(name, "cutting", m.cutting, "");
      text += stats_row(name, "rapid", m.rapid, "");
    }
    text += stats_row(name, "all", m.stats, std::to_string(m.out_of_range_lookups));
  }
  if (s.conventions.any) {
    text += fmt::format(
        "reference conventions of the tables: the absolute deviation is not determined (an "
        "offset and a rotation are free); the part after its set-up (--align) is {}\n",
        s.conventions.aligned_determined ? "determined" : "NOT determined");
    for (const std::string& n : s.conventions.notes) text += "  " + n + "\n";
  }
  return text;
}

}  // namespace abbe::pipeline
