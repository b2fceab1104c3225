#pragma once
// One selection step's view of its candidates: what each removes from the
// residual, its cost on the information criterion, its fitted contribution,
// whether it is a part of the structure the best smooth function finds, the
// cheaper candidate that takes its place, and its rivals.
#include <array>
#include <map>
#include <string>
#include <vector>

#include "abbe/diagnose/candidates.hpp"
#include "abbe/diagnose/selection.hpp"
#include "candidate_fit.hpp"

namespace abbe::diagnose::selection {

// The variables (x, y, z, t) a term's deviation is a function of; false
// for a term that is not a function of a few of them (a reversal follows the
// motion; a setup rotation or a model choice, every position).
bool within_variables(const Term& t, const std::vector<int>& vars);

// Share of the deviation a term's columns make (at unit coefficients, over
// the points) that lies along `direction`.
double share_along(const Problem& pb, const Term& t, int direction);

// A drift whose course over the measurement's points is nearly constant
// (its standard deviation below kNearlyStaticCourse of its mean: at
// τ = 300 s over a two-hour walk, done but for the first minutes) stands for
// a static term.
inline constexpr double kNearlyStaticCourse = 0.3;
bool drift_nearly_static(const Problem& pb, const Term& t);

// The share of a candidate's fitted contribution a smooth function must
// reproduce for the candidate to be a part of its structure by reproduction.
inline constexpr double kReproducedShare = 0.9;

// A candidate at one step: what it removes from the residual (ΔRSS) and
// the floor it must pass alone (its χ² and the practical floor, in σ̂²).
struct Score {
  const Cached* c = nullptr;
  double d = -1.0;
  double thr = 0.0;
};

// What a selection step knows when it weighs its candidates.
struct Step {
  Step(const Problem& problem, const SelectionOptions& options, const CandidateSet& candidates,
       const Mat& span, const Vec& residual, const std::vector<Score>& scored,
       std::map<std::string, std::array<double, 3>>& shares)
      : pb(problem),
        o(options),
        cs(candidates),
        Q(span),
        r(residual),
        scores(scored),
        share_cache(shares) {}

  const Problem& pb;
  const SelectionOptions& o;
  const CandidateSet& cs;
  const Mat& Q;                                               // the selected span, orthonormal
  const Vec& r;                                               // the residual, ⟂ Q
  const std::vector<Score>& scores;                           // by ΔRSS, largest first
  std::map<std::string, std::array<double, 3>>& share_cache;  // by label, per direction
  double rr = 0.0, dof_base = 0.0;  // the residual's SS and degrees of freedom
  double lambda = 0.0;              // the practical floor's non-centrality, n·min_effect_rms²
  double tests_named = 1.0;         // named candidates tested per step (the χ²'s correction)
  double s2_ic = 0.0;               // σ̂² of the information criterion
  // The best smooth function above its floors (have_generic), with its ΔRSS.
  bool have_generic = false;
  Term g_best;
  double g_best_d = 0.0;
  // The variables of every other smooth function along g_best's direction
  // that finds the structure as well (SelectionOptions::structure_near_share).
  std::vector<std::vector<int>> structure_vars;
  // Where set (SelectionOptions::drift_parts_by_reproduction): a drift whose
  // fitted contribution these columns, the best smooth function's, reproduce
  // is a part of its structure too, whatever its variables (not one nearly
  // static).
  const Mat* reproduced_by = nullptr;
  // Whether a drift is reproduced, by label, for the reproduced_by set
  // (cleared where it is set).
  mutable std::map<std::string, bool> reproduced_cache;

  // Parsimony: an information criterion that charges every column ln(n)
  // residual variances and a searched period or time constant
  // `searched_cost` columns more (a one-column squareness beats a cyclic
  // term that fits the same line only by fitting the noise).
  double cost(const Term& t) const;
  double ic_gain(double d, double cost) const;
  // The fitted contribution of a candidate (orthogonal to the selected span).
  Vec contribution(const Cached& c) const;
  // ΔRSS of several candidates together (orthogonal to the selected span).
  double together(const std::vector<const Score*>& members) const;
  // A candidate is a part of the structure the best smooth function
  // explains when it is a function of its variables only (or of those of
  // a smooth function that finds it as well: structure_vars), moving at least
  // half along its direction (not, e.g., an arm offset that moves X and Y
  // beside a structure in Z; a reversal counts, it follows the rows of a
  // walk); with reproduced_by set, also a drift those columns reproduce.
  bool in_structure(const Score& sc) const;
  // The share of the candidate's deviation along the best smooth function's
  // direction (share_along, cached by label).
  double share_along_best(const Score& sc) const;
  // The columns `smooth_columns` reproduce at least kReproducedShare of the
  // candidate's fitted contribution (beside the selected span).
  bool reproduces(const Mat& smooth_columns, const Score& sc) const;
  // Above its χ² alone (not necessarily the practical floor).
  bool significant(const Score& sc) const;
  // Parsimony: only explanations of the same structure compete on the
  // criterion; a cheaper candidate above its floors whose fitted
  // contribution correlates with `largest`'s above `competing_corr` and has
  // the better criterion takes its place (largest itself when none does).
  // Then, with drift_course_floor, a drift that grows with a position gives
  // way to its static form (a scale, a squareness) where its course in time
  // adds less than a name's floor beside it (both under parsimony_ic).
  const Score* parsimonious(const Score* largest) const;
  // Ambiguity: the candidates of no higher cost that remove at least 0.9
  // of the target's ΔRSS, whose fitted contributions coincide with its
  // (`ambiguous_corr`) and which the data do not reject against it
  // (`rivals_by_test`): their labels appended to `alt.names`; and a cycle's
  // aliases, to `alt.periods_mm`. Returns what measurement would separate
  // them (may be empty).
  std::string rivals(const Score& target, Alternatives& alt) const;
  // What the data must remove more for a rival to be rejected: σ̂²·χ²₁(alpha)
  // of the information criterion's σ̂², one column's test.
  double rival_margin() const;
};

}  // namespace abbe::diagnose::selection
