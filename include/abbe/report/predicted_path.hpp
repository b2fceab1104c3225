#pragma once
// PredictedPath: what the predict report draws — the fragmented toolpath of
// an NC program (nominal tool tips, source lines, path length) and the
// deviation of each error model at every kept point, with the statistics of
// all points. Long programs are decimated for display while streaming: every
// 2ᵏ-th point is kept so that at most `max_points` remain, and in every
// stretch of 2ᵏ points the one of the largest |d| of each model is kept
// too, so the peaks of the deviation survive (at most (1 + models) ×
// max_points points; each model's largest |d| is among them); the
// statistics always cover every point.
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <istream>
#include <map>
#include <string>
#include <vector>

#include "abbe/gcode/dialect.hpp"
#include "abbe/gcode/interpreter.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/model/model_kind.hpp"
#include "abbe/pipeline/prediction_uncertainty.hpp"

namespace abbe::report {

struct PredictPathOptions {
  std::vector<model::ModelKind> models{model::ModelKind::ae_arm};
  double step = 5.0;            // mm, fragmentation
  double rapid_rate = 10000.0;  // mm/min
  std::size_t max_points = 20000;
  // An axis that moves less than this within a straight motion keeps the
  // direction sign it had (for compensated programs: the micro-motions a
  // correction adds to an axis at rest are no reversals, as in `abbe
  // verify`). 0: every motion counts (as `abbe predict`).
  double min_reversal_mm = 0.0;
  gcode::DialectOptions dialect;  // how the program is written
  // Monte Carlo draws of the campaign's uncertainty (0: none) and their seed.
  std::size_t uncertainty_draws = 0;
  std::uint64_t seed = 1;
  // The part's set-up (`--align best-fit|datums`, as `abbe predict --align`):
  // method none draws the absolute deviation only.
  pipeline::AlignOptions align;
  // Called now and then with the bytes of the input consumed so far.
  std::function<void(std::uint64_t)> progress;
};

struct ModelPathStats {
  model::ModelKind model = model::ModelKind::ae_arm;
  std::size_t points = 0;
  Eigen::Vector3d max_abs_um = Eigen::Vector3d::Zero();
  double rms_um = 0.0;       // of |d|
  double max_um = 0.0;       // of |d|
  std::size_t max_line = 0;  // source line of the largest |d|
  std::size_t out_of_range_lookups = 0;
};

struct PredictedPath {
  std::string program;  // file name ("-" for stdin)
  std::string machine;  // machine name
  std::string sha256;   // of the program's bytes as read
  std::vector<model::ModelKind> models;
  std::size_t total_points = 0;  // all points of the program
  std::size_t stride = 1;        // every stride-th point is kept (and the extremes)
  // Kept points:
  std::vector<std::size_t> index;                          // 0-based point number
  std::vector<Eigen::Vector3d> nominal;                    // tool tip P, mm
  std::vector<std::size_t> line;                           // source line
  std::vector<double> path_length;                         // mm from the start
  std::vector<std::vector<Eigen::Vector3d>> deviation_um;  // [model][point]
  std::vector<bool> rapid;                                 // the kept point is on a rapid
  std::vector<ModelPathStats> stats;                       // per model, all points
  // Per model, the points of cutting moves and of rapids (as `abbe predict`).
  std::vector<ModelPathStats> cutting_stats, rapid_stats;
  std::map<std::size_t, std::string> source;  // text of the source lines of kept points
  // With uncertainty_draws: per model the standard uncertainties of dx, dy,
  // dz at the kept points (µm), and the summary figures with their
  // uncertainty; both empty without.
  std::vector<std::vector<Eigen::Vector3d>> u_um;  // [model][kept point]
  pipeline::PredictionUncertainty uncertainty;
  bool has_uncertainty() const { return !u_um.empty(); }
  // With align: per model the deviation after the part's set-up at the kept
  // points (those of `abbe predict --align`, µm) and the set-up (its rigid
  // motion, the part's figures before and after); with uncertainty_draws
  // too, their standard uncertainties (the part set up again in every draw)
  // and `uncertainty.models[m].aligned`. All empty without align.
  std::vector<std::vector<Eigen::Vector3d>> aligned_um;    // [model][kept point]
  std::vector<std::vector<Eigen::Vector3d>> u_aligned_um;  // [model][kept point]
  pipeline::PartAlignmentSummary alignment;
  bool has_alignment() const { return !aligned_um.empty(); }
};

// Streams the program through parser, interpreter, fragmenter and the error
// models; with uncertainty draws or an alignment, predicts the program a
// second time (predict_with_uncertainty, predict_aligned) for the u and the
// deviation after the set-up of the kept points. Throws abbe::InputError on
// bad input (file, line, column) and on a part or datum set that does not
// define the alignment.
PredictedPath predict_program(const machine::Machine& machine, std::istream& in,
                              const std::string& file, const PredictPathOptions& options);

}  // namespace abbe::report
