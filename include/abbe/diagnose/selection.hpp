#pragma once
// Forward stepwise selection of effects in the residual (docs/diagnosis.md):
// at each step the candidate that removes the most residual sum of squares
// (orthogonal to what is already selected) is added if it passes
//  - a significance floor tied to the noise: ΔRSS > σ̂²·χ²_k(α / N_tests),
//  - the held-out check: the k-fold cross-validated SSE decreases,
// and a named kind wins only if it explains at least `name_ratio` of what the
// best smooth `unexplained` function explains; otherwise the smooth function
// is taken and reported as unexplained structure. Candidates whose fitted
// contributions are nearly identical to the winner's are reported with it
// as ambiguous.
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "abbe/diagnose/candidates.hpp"
#include "abbe/diagnose/residuals.hpp"

namespace abbe::diagnose {

struct SelectionOptions {
  int folds = 5;
  std::uint64_t seed = 1;
  double alpha = 0.01;  // family-wise false-detection rate per step
  int max_terms = 12;
  double name_ratio = 0.7;  // a named kind must explain this share of the best smooth fit
  double ambiguous_corr = 0.98;
  std::size_t scan_points = 20000;  // points used to locate a period peak
  // Optional: called at the start of each selection step (0-based), e.g. for
  // a progress bar.
  std::function<void(int step)> on_step;
};

struct SelectedTerm {
  Term term;                        // with coef and stderr_ from the final joint fit
  double explained_fraction = 0.0;  // share of the baseline residual SS only this term removes
  std::vector<std::string> ambiguous_with;
};

struct SelectionResult {
  std::vector<SelectedTerm> terms;  // ordered by explained_fraction
  Eigen::VectorXd residual;         // after the final fit, per observation
  double sigma_um = 0.0;            // noise estimate per observation after the fit
  double cv_sse = 0.0;              // held-out SSE of the selected model
  double baseline_sse = 0.0;        // SSE of the residual without extension
  std::vector<std::string> log;     // one line per step
};

SelectionResult select_effects(const Problem& problem, const CandidateSet& candidates,
                               const SelectionOptions& options);

// Fold of every point (k-fold, shuffled by `seed`).
std::vector<int> point_folds(std::size_t points, int folds, std::uint64_t seed);

// The observation-level columns of a term (observations × columns).
Eigen::MatrixXd term_columns(const Problem& problem, const Term& term);

// Held-out SSE of a least-squares fit of the columns X to y over the folds.
double cross_validated_sse(const Problem& problem, const Eigen::MatrixXd& X,
                           const Eigen::VectorXd& y, const std::vector<int>& fold_of_point,
                           int folds);

}  // namespace abbe::diagnose
