#pragma once
// predict_with_uncertainty: `abbe predict --uncertainty N`: the prediction of
// `predict`, and the uncertainty of every predicted point and of the summary
// figures propagated from the campaign's uncertainty (the machine file's
// `uncertainty` key and the table's `uncertainty` column) by Monte Carlo
// (GUM Supplement 1): N seeded draws of the campaign
// (machine::draw_campaign), each evaluated at the same points by the same
// ModelSet as the plain prediction (docs/models.md, "Uncertainty of the
// prediction"). With --align, every draw's part is set up again (best fit or
// datums), so that the uncertainty of the deviation after alignment is given
// beside the absolute one.
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <istream>
#include <string>
#include <vector>

#include "abbe/machine/machine.hpp"
#include "abbe/model/error_model.hpp"
#include "abbe/model/model_kind.hpp"
#include "abbe/pipeline/aligned_prediction.hpp"
#include "abbe/pipeline/predict.hpp"
#include "abbe/pipeline/prediction_summary.hpp"

namespace abbe::pipeline {

struct UncertaintyOptions {
  std::size_t draws = 200;       // Monte Carlo trials (at least 2)
  std::uint64_t seed = 1;        // the same seed gives the same draws
  double coverage_factor = 2.0;  // k of the expanded uncertainty U = k·u
};

// A summary figure of the prediction and its uncertainty over the draws.
struct FigureUncertainty {
  double value = 0.0;     // of the plain prediction (the best estimates)
  double u = 0.0;         // standard uncertainty: standard deviation over the draws
  double expanded = 0.0;  // U = k·u
  double low = 0.0;       // 95 % coverage interval of the draws (2.5 % and
  double high = 0.0;      // 97.5 % quantiles, probabilistically symmetric)
};

// The figures of one group of points, in this order: max|dx|, max|dy|,
// max|dz|, rms |d|, max |d| (µm).
inline constexpr std::size_t kUncertainFigures = 5;
struct GroupUncertainty {
  std::size_t points = 0;
  std::array<FigureUncertainty, kUncertainFigures> figures{};
};

struct ModelUncertainty {
  model::ModelKind kind = model::ModelKind::ae_arm;
  GroupUncertainty all, cutting, rapid;  // cutting and rapid: programs only
  GroupUncertainty aligned;              // the part after its set-up (--align only)
};

struct PredictionUncertainty {
  std::size_t draws = 0;
  std::uint64_t seed = 0;
  double coverage_factor = 2.0;
  std::string sources;  // machine::campaign_uncertainty_text
  std::vector<ModelUncertainty> models;
};

struct UncertainPrediction {
  PredictionSummary summary;  // the same as predict's
  PredictionUncertainty uncertainty;
  PartAlignmentSummary alignment;  // the same as predict_aligned's; method none without --align
};

// Every point, after the draws: the models' deviations and |e| (those of the
// plain prediction) and the standard uncertainties u(dx), u(dy), u(dz), µm.
using UncertainSink = std::function<void(
    const model::EvalPoint& point, std::size_t line, const std::vector<model::Deviation>& devs,
    const std::vector<double>& norms_um, const std::vector<Eigen::Vector3d>& u_um)>;

// Every point of an aligned prediction, after the draws: as UncertainSink,
// with the deviations after alignment (those of predict_aligned) and their
// standard uncertainties (the part set up again in every draw), µm.
using AlignedUncertainSink = std::function<void(
    const model::EvalPoint& point, std::size_t line, const std::vector<model::Deviation>& devs,
    const std::vector<double>& norms_um, const std::vector<Eigen::Vector3d>& aligned_um,
    const std::vector<Eigen::Vector3d>& u_um, const std::vector<Eigen::Vector3d>& u_aligned_um)>;

// Throws abbe::InputError on bad input, and (field "uncertainty", naming the
// machine file) when the machine gives no uncertainty to propagate.
// `progress` is predict's sink (may be empty); `draw_done` is called after
// every draw with the number of draws done (may be empty).
UncertainPrediction predict_with_uncertainty(
    std::istream& in, const std::string& file, const machine::Machine& machine,
    const PredictOptions& options, const UncertaintyOptions& uncertainty,
    const PredictionSink& progress, const UncertainSink& sink,
    const std::function<void(std::size_t)>& draw_done = {});

// The same with the part's set-up (`predict --uncertainty N --align …`): the
// alignment of predict_aligned (same errors for a part or datum set that does
// not define it), redone in every draw. The absolute u are those of the
// call above with the same seed.
UncertainPrediction predict_with_uncertainty(
    std::istream& in, const std::string& file, const machine::Machine& machine,
    const PredictOptions& options, const UncertaintyOptions& uncertainty, const AlignOptions& align,
    const PredictionSink& progress, const AlignedUncertainSink& sink,
    const std::function<void(std::size_t)>& draw_done = {});

// The summary JSON of `summary_json` with an "uncertainty" member: method,
// draws, seed, coverage_factor, sources, models[{model, all{points,
// max_abs_dx_um{value, u, U, interval_95[low, high]}, …}, cutting{…},
// rapid{…}}]. Aligned: the "alignment" member of predict_aligned's summary
// too, and per model "aligned"{…} (the part after its set-up).
std::string summary_json(const UncertainPrediction& prediction);

// summary_table (predict_aligned's when aligned) followed by the table of the
// figures with their expanded uncertainty.
std::string summary_table(const UncertainPrediction& prediction);

}  // namespace abbe::pipeline
