#pragma once
// Gross outliers of a diagnosis (docs/diagnosis.md, "Outliers"): points
// whose residual against the fit lies more than k robust σ away — the
// robust σ being 1.4826·median|r| of the fitted residual, so the outliers
// themselves do not inflate it. diagnose() flags them after the datum fit,
// leaves them out, runs the selection, flags again against the selected
// model, and repeats until the set of outliers no longer changes. They are
// listed in the reports and take no part in the effects, the gain or the
// noise estimates.
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "abbe/diagnose/residuals.hpp"
#include "abbe/diagnose/selection.hpp"

namespace abbe::diagnose {

struct OutlierOptions {
  bool enabled = true;
  double k = 6.0;      // threshold in robust σ of the residual
  int max_passes = 4;  // selections run at most (a pass changes the set of outliers)
  // Never flag below this (µm): data without noise have a robust σ of
  // rounding errors, and nothing that small is a gross outlier.
  double min_threshold_um = 0.01;
  // When points were flagged: select once more with every point and
  // restart the flagging from what that model leaves beyond the threshold;
  // keep the result that leaves out fewer points (a coherent group that a
  // catalogue effect explains, e.g. a reversal, is not gross error).
  bool group_check = true;
};

struct Outlier {
  std::uint32_t point = 0;  // index in the full problem
  std::size_t line = 0;     // source line (0: unknown)
  std::string set;
  Eigen::Vector3d s = Eigen::Vector3d::Zero();  // axis positions, mm
  double residual_um = 0.0;                     // largest |residual| of its components
};

// 1.4826·median|r|: σ of normal residuals, unmoved by a few gross ones (0 for none).
double robust_sigma(const Eigen::VectorXd& r);

// Points with a component whose |residual| exceeds `threshold`, ascending.
std::vector<std::uint32_t> points_beyond(const Problem& problem, const Eigen::VectorXd& r,
                                         double threshold);

// The problem without the points `drop` (ascending); observations renumbered.
// Its data range (var_lo/var_hi) and travel stay those of `problem`.
Problem without_points(const Problem& problem, const std::vector<std::uint32_t>& drop);

// y − Σ of every fitted term (datum and effects), per observation, at every
// point of `problem` (also those left out of the fit).
Eigen::VectorXd residual_after(const Problem& problem, const std::vector<SelectedTerm>& datum,
                               const std::vector<SelectedTerm>& effects);

}  // namespace abbe::diagnose
