#pragma once
// predict_aligned: `abbe predict --align`: the prediction of `predict`, then
// the part's set-up (a best fit over the cutting points, or a 3-2-1 alignment
// from three datum point sets named by source lines) computed per model, and
// every point handed to a sink with its deviation after alignment beside the
// absolute one (docs/models.md, "The part").
#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <istream>
#include <string>
#include <utility>
#include <vector>

#include "abbe/machine/machine.hpp"
#include "abbe/model/error_model.hpp"
#include "abbe/model/model_kind.hpp"
#include "abbe/pipeline/model_set.hpp"
#include "abbe/pipeline/part_alignment.hpp"
#include "abbe/pipeline/predict.hpp"
#include "abbe/pipeline/prediction_summary.hpp"
#include "abbe/pipeline/stored_prediction.hpp"

namespace abbe::pipeline {

enum class AlignMethod { none, best_fit, datums };

// "none", "best-fit", "datums".
const char* to_string(AlignMethod method);
// Throws std::invalid_argument for another name.
AlignMethod parse_align_method(const std::string& name);

// A set of source lines, written "12-30,45,50-52" (NC program lines, or the
// lines of a CSV of points).
class LineSet {
 public:
  // Throws abbe::InputError naming `field` (e.g. "--datum-primary") and the
  // column of a bad number or range.
  static LineSet parse(const std::string& text, const std::string& field);
  bool contains(std::size_t line) const;
  bool empty() const { return ranges_.empty(); }

 private:
  std::vector<std::pair<std::size_t, std::size_t>> ranges_;  // inclusive
};

struct AlignOptions {
  AlignMethod method = AlignMethod::none;
  LineSet primary, secondary, tertiary;  // datums only
};

// One model's set-up: the rigid motion applied to its predicted part, and the
// statistics over the part's points before (absolute) and after alignment.
struct ModelAlignment {
  model::ModelKind kind = model::ModelKind::ae_arm;
  RigidMotion motion;
  Eigen::Vector3d rotation_urad = Eigen::Vector3d::Zero();      // of the motion
  Eigen::Vector3d centroid_shift_um = Eigen::Vector3d::Zero();  // T(c) − c, c the part's centroid
  ModelStats absolute;
  ModelStats aligned;
};

struct PartAlignmentSummary {
  AlignMethod method = AlignMethod::none;
  std::size_t part_points = 0;  // cutting points (every point of a CSV input)
  std::size_t datum_points[3] = {0, 0, 0};
  std::vector<ModelAlignment> models;
};

// The part of a stored prediction and its set-up: the cutting points (every
// point of a CSV of points), the datum sets among them, and the alignment of
// one model's deviations. Used once by predict_aligned and once per draw by
// predict_with_uncertainty with --align.
class PartSetup {
 public:
  PartSetup(const StoredPrediction& stored, const AlignOptions& align, std::string file);
  // The set-up of the part whose points deviate by e_um[i] (µm, one per stored
  // point): its rigid motion and the statistics over the part before and after
  // alignment. Throws abbe::InputError (naming the input file and the
  // alignment option) when the part or a datum set does not define it.
  ModelAlignment align(model::ModelKind kind, const std::vector<Eigen::Vector3d>& e_um) const;
  const std::vector<std::size_t>& part() const { return part_; }
  // The summary of the alignment, without models.
  PartAlignmentSummary summary() const;

 private:
  const StoredPrediction& stored_;
  AlignMethod method_;
  std::string file_;
  std::vector<std::size_t> part_;  // indices of the stored points
  DatumIndices datums_;            // indices into part_
  Eigen::Vector3d centroid_ = Eigen::Vector3d::Zero();
};

// The deviations of model m at every stored point, µm.
std::vector<Eigen::Vector3d> deviations_um(const StoredPrediction& stored, std::size_t m);

struct AlignedPrediction {
  PredictionSummary summary;
  PartAlignmentSummary alignment;
};

// Every point, after all points were predicted and the alignment computed:
// the models' deviations, |e|, and the deviations after alignment (µm).
using AlignedSink = std::function<void(
    const model::EvalPoint& point, std::size_t line, const std::vector<model::Deviation>& devs,
    const std::vector<double>& norms_um, const std::vector<Eigen::Vector3d>& aligned_um)>;

// Throws abbe::InputError on bad input, and on a part or datum set that does
// not define the alignment (naming the input file and the datum option).
// `progress` is called as predict's sink (may be empty).
AlignedPrediction predict_aligned(std::istream& in, const std::string& file,
                                  const machine::Machine& machine, const PredictOptions& options,
                                  const AlignOptions& align, const PredictionSink& progress,
                                  const AlignedSink& sink);

// The summary JSON of `summary_json` with an "alignment" member: method,
// part_points, models[{model, rotation_urad{x,y,z}, centroid_shift_um{x,y,z},
// absolute{…}, aligned{…}}] (each {max_abs_d{x,y,z}_um, rms_d_um, max_d_um}).
std::string summary_json(const AlignedPrediction& prediction);

// summary_table followed by the table of the part before and after alignment.
std::string summary_table(const AlignedPrediction& prediction);

}  // namespace abbe::pipeline
