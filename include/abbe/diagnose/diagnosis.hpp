#pragma once
// diagnose(): the whole diagnosis of measured data against a machine's error
// model — residuals of the three models, candidate effects, stepwise
// selection, the extended model and its held-out gain (docs/diagnosis.md).
#include <cstddef>
#include <string>
#include <vector>

#include "abbe/diagnose/blind_spots.hpp"
#include "abbe/diagnose/candidates.hpp"
#include "abbe/diagnose/design_ambiguity.hpp"
#include "abbe/diagnose/dynamic.hpp"
#include "abbe/diagnose/isotropic_scale.hpp"
#include "abbe/diagnose/noise.hpp"
#include "abbe/diagnose/outliers.hpp"
#include "abbe/diagnose/overlay.hpp"
#include "abbe/diagnose/residuals.hpp"
#include "abbe/diagnose/rival_check.hpp"
#include "abbe/diagnose/selection.hpp"
#include "abbe/diagnose/table_uncertainty.hpp"
#include "abbe/diagnose/transfer.hpp"
#include "abbe/io/measured_data.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/model/model_kind.hpp"

namespace abbe::diagnose {

struct DiagnoseOptions {
  model::ModelKind model = model::ModelKind::ae_arm;
  SelectionOptions selection;
  CandidateOptions candidates;
  OutlierOptions outliers;
  DesignAmbiguityOptions design;    // what the design cannot tell apart (design_ambiguity.hpp)
  RivalOptions rivals;              // rivals the data cannot reject (rival_check.hpp)
  const Overlay* extend = nullptr;  // an earlier overlay added to the model's prediction
  // Axes without approach directions in the data get them from the order
  // of the points (io/approach_directions.hpp); off by default.
  bool infer_directions = false;
  // The tables' uncertainty added to every named value's u by Monte Carlo
  // (table_uncertainty.hpp; diagnose() only): by default where the machine
  // file gives one; draws 0: the data's u alone.
  TableUncertaintyOptions tables;
};

struct Diagnosis {
  std::string machine;
  std::string measured_file;
  std::string model;
  std::size_t n_points = 0;  // fitted: the measured points without the outliers
  std::size_t n_observations = 0;
  // Gross outliers (outliers.hpp): left out of everything below except `models`.
  std::vector<Outlier> outliers;
  double outlier_threshold_um = 0.0;  // k robust σ of the final fit's residual
  double outlier_k = 0.0;
  std::vector<ResidualStats> models;     // htm, ae-arm, dual (without any overlay)
  ResidualStats baseline;                // the diagnosed model (with --extend if given)
  std::vector<SelectedTerm> effects;     // ordered by importance
  double explained_together = 0.0;       // share of the residual (after the datum) they remove
  std::vector<SelectedTerm> datum;       // what the datum (offsets, plate rotations) absorbed
  OverlayDomain domain;                  // box and time window of the data (the overlay's)
  ResidualStats extended;                // after the selected effects, in-sample
  double holdout_rms_um = 0.0;           // extended model, held-out folds
  double baseline_holdout_rms_um = 0.0;  // the model with the datum fitted, held-out folds
  double gain_percent = 0.0;
  double noise_um = 0.0;  // residual σ per observation after the fit
  // σ per observation from the data alone (noise.hpp): repeated points or
  // neighbour differences; 0 when the data allow neither.
  double noise_independent_um = 0.0;
  std::string noise_method;
  // Circular tests (dn along the radius of a circle): the sets, and the
  // dynamic signatures found in the residual (dynamic.hpp; never named).
  std::vector<std::string> circles;
  std::vector<DynamicFinding> dynamic;
  int folds = 0;
  // Named scales of several axes that agree: one isotropic scale
  // (isotropic_scale.hpp).
  IsotropicScale isotropic;
  // With `extend`: what the earlier overlay does on these data (transfer.hpp),
  // on the points left after the outliers.
  TransferCheck extend_check;
  // The axes whose approach directions were inferred (infer_directions).
  std::vector<int> directions_inferred;
  // Measured points whose axis positions lie outside the machine's travel
  // (machine/travel_check.hpp): the machine cannot go there, so the data
  // are in another frame (the part's coordinates, not the machine's) or
  // belong to another machine; travel_text says how many and where, and
  // travel_warning() what it means. Diagnosed all the same.
  std::size_t outside_travel_points = 0;
  std::string travel_text;
  // The tables' uncertainty propagated into the u (draws 0: not).
  TableUncertainty tables;
  // What the design cannot test at all (blind_spots.hpp).
  std::vector<BlindSpot> blind_spots;
  std::vector<std::string> log;
};

Diagnosis diagnose(const machine::Machine& machine, const io::MeasuredData& data,
                   const DiagnoseOptions& options);
// The same on an already built residual problem.
Diagnosis diagnose_problem(const Problem& problem, const DiagnoseOptions& options);

// The warning for measured points outside the travel ("" when none are):
// travel_text and what it means for the diagnosis.
std::string travel_warning(const Diagnosis& d);

// DESIGN.md §4 report (stable keys, plus a few extra informative ones).
std::string report_json(const Diagnosis& d);
// The human summary: models, effects, gain.
std::string report_text(const Diagnosis& d);
// The effect's value (its first parameter) with its standard uncertainty,
// e.g. "+12.3 ± 0.41 ppm"; "-" for a term without one (unexplained).
std::string effect_value_text(const Term& t);
// |value| > its standard uncertainty (true for a term without one).
bool value_significant(const Term& t);
// A smooth function's linear part: "its linear part (52 % of it; parts of a
// structure, not names): scale Y -26.1 ± 0.77 ppm, …", listing the parts whose
// value exceeds its uncertainty; "" when none does or they hold less than
// kLinearPartMinShare of the function (SelectedTerm::linear_parts).
std::string linear_part_text(const SelectedTerm& st);
// With the tables' uncertainty propagated: "u from the data and from the
// tables: value 0.084 and 0.31 µm; τ 70 and 3.4e+02 s"; "" otherwise.
std::string uncertainty_parts_text(const SelectedTerm& st);
// A cycle named with its period unresolved (SelectedTerm::other_periods_mm):
// "period not resolved: 7.52 mm fits as well"; "" otherwise.
std::string period_unresolved_text(const SelectedTerm& st);
// The circular-test lines of the summary ("" without circles).
std::string dynamic_text(const Diagnosis& d);
// The blind-spot lines of the summary ("" when none).
std::string blind_spots_text(const Diagnosis& d);
// The isotropic-scale line of the summary ("" when none).
std::string isotropic_text(const Diagnosis& d);
// The outliers line of the summary ("" when none), listing at most `max_listed`.
std::string outliers_text(const Diagnosis& d, std::size_t max_listed);
// The selected effects as an overlay (extended model).
Overlay make_overlay(const Diagnosis& d, const Overlay* extend);

}  // namespace abbe::diagnose
