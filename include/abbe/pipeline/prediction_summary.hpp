#pragma once
// The summary of a prediction: per model, the largest deviation per axis, the
// RMS and the largest |e| over all points, and the table lookups outside the
// measured range. Written as JSON (`--summary-json`, the "summary" member of
// the JSON output) and as the text table `abbe predict` prints.
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "abbe/machine/machine.hpp"
#include "abbe/model/model_kind.hpp"
#include "abbe/pipeline/model_set.hpp"

namespace abbe::pipeline {

struct ModelSummary {
  model::ModelKind kind = model::ModelKind::ae_arm;
  ModelStats stats;  // all points
  // The points of cutting moves (feeds, arcs, the feeds of canned cycles)
  // and of rapids: the split every command and report shows.
  ModelStats cutting, rapid;
  std::size_t out_of_range_lookups = 0;
};

struct PredictionSummary {
  std::string machine;  // machine name
  std::string input;    // file name ("-" for stdin)
  std::size_t points = 0;
  // A program (points on cutting moves and rapids) rather than a CSV of points.
  bool moves = false;
  machine::OutOfRangePolicy out_of_range = machine::OutOfRangePolicy::clamp;
  std::vector<ModelSummary> models;
  // Points whose axis positions lie outside the machine's travel
  // (machine/travel_check.hpp), in all and per axis; travel_text says so
  // with the first lines (empty when none is outside).
  std::size_t outside_travel_points = 0;
  std::array<std::size_t, 3> outside_travel_per_axis{0, 0, 0};
  std::string travel_text;
  // The machine file's reference conventions (empty `notes`: absolute
  // tables, nothing is said): what each leaves free, and whether the part
  // after its set-up (--align) is determined.
  machine::ConventionAnalysis conventions;
};

PredictionSummary summarize(const ModelSet& models, const machine::Machine& machine,
                            const std::string& input);

// JSON object (2-space indent, no trailing newline): machine, input, points,
// out_of_range_policy, models[{model, points, max_abs_d{x,y,z}_um, rms_d_um,
// max_d_um, max_line, out_of_range_lookups, and for a program cutting{...} and
// rapid{...} with points, max_abs_d{x,y,z}_um, rms_d_um, max_d_um, max_line}].
std::string summary_json(const PredictionSummary& summary);

// The text table: a title line, then per model a row for the cutting moves,
// one for the rapids and one for all points (a CSV of points: all only), µm.
std::string summary_table(const PredictionSummary& summary);

}  // namespace abbe::pipeline
