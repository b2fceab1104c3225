#pragma once
// Forward stepwise selection of effects in the residual (docs/diagnosis.md):
// at each step the candidate that removes the most residual sum of squares
// (orthogonal to what is already selected) is added if it passes
//  - a significance floor tied to the noise: ΔRSS > σ̂²·χ²_k(α / N_tests),
//  - the held-out check: the k-fold cross-validated SSE decreases,
// and a named kind wins only if it (or a combination of up to three named
// kinds, compared on an information criterion that counts searched
// parameters) explains at least `name_ratio` of what the best smooth
// `unexplained` function explains; otherwise the smooth function is taken
// and reported as unexplained structure. Candidates whose fitted
// contributions are nearly identical to the winner's are reported with it
// as ambiguous. After the forward steps, each named effect is tested again
// beside the others (backward_check.hpp) and one that later steps made
// redundant is dropped.
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
  // A candidate of no higher cost whose fitted contribution correlates with
  // the pick's above `ambiguous_corr` and removes at least 0.9 of its ΔRSS
  // is reported as an alternative (`ambiguous`) only when the data do not
  // prefer the pick significantly: its ΔRSS is short of the pick's by less
  // than σ̂²·χ²₁(alpha), one column's test. False: near-equal and
  // correlated is enough (a drift z·t late in a warm-up then stays
  // ambiguous with a scale Z, however clearly the data reject the scale).
  bool rivals_by_test = true;
  // Practical significance: an effect is named only when the RMS of what it
  // removes per observation is at least this fraction of the noise σ̂ (a
  // structure far below the noise changes no prediction, however many
  // points make it "significant"; e.g. the interpolation error of noisy
  // laser tables on a dense grid).
  double min_effect_rms = 0.3;
  // The practical floor as a test at level `alpha`: the candidate's ΔRSS/σ̂²
  // must exceed the upper α quantile of χ²_k(λ = n·min_effect_rms²), what
  // an effect exactly at the floor would give with the noise on it (on a
  // small design, e.g. a 117-hole plate, a point estimate at the floor is
  // often noise on a smaller structure); false: ΔRSS ≥ n·min_effect_rms²·σ̂².
  bool min_effect_test = true;
  // A cyclic period is ambiguous when another peak of the periodogram (not a
  // neighbour) reaches this share of the best peak's power (aliasing).
  double alias_power = 0.9;
  // Those peaks are then fitted exactly and kept only where the data do not
  // reject them against the pick (one column's test, as for other rivals),
  // on an axis whose positions are not a few levels. On at most
  // `alias_levels` levels they stay as found: there a pitch error with
  // harmonics is a sum of cycles, and one cycle's exact fit at the wrong
  // period can beat the true one alone (the design's own test,
  // design_ambiguity, then judges the named periods beside each other).
  std::size_t alias_levels = 40;
  std::size_t scan_points = 20000;  // points used to locate a period peak
  // The period of a cycle between two frequencies of the scan grid: the
  // peak refined by a parabola through the best power and its neighbours
  // (false: the grid's best frequency; a quarter step off over a long
  // travel the cycle beats against the data).
  bool refine_period = true;
  // Then on the exact ΔRSS beside the fit so far (Brent within one grid
  // step): the periodogram's peak is the raw projection's, a fraction
  // of a lobe off the least-squares period on few or irregular levels.
  bool exact_period = true;
  // A chosen drift's τ on the exact ΔRSS between the scan grid's
  // neighbours of its τ (Brent on ln τ, time_constant.hpp), after the
  // choice as for a period: at the grid's τ a part of the drift is left
  // for a scale or a smooth function to take (false: the grid's τ).
  bool exact_tau = true;
  // And once more in the final fit beside every other named term: the
  // reported τ and its uncertainty are the data's best (false: as chosen).
  bool refine_tau = true;
  // A cycle of the axis and direction of a chosen one is not scanned
  // within 1/span of its frequency (span: the axis's measured travel),
  // where two sinusoids are not resolved from each other and a second one
  // would only take up what the first one's period left (false: it is).
  bool resolve_chosen_cycles = true;
  // And each chosen cycle's period, within half the resolution 1/span of
  // its axis (chosen_periods.hpp): a pitch error's harmonic chosen after
  // its fundamental moves the fundamental's best period.
  bool refine_periods = true;
  // A chosen cycle whose exact refinement stops at the end of its family's
  // range (the best period lies beyond what the catalogue searches): the
  // periods the scan found as good (its aliases) are refined too and the
  // best kept (parameter_scan.hpp; false: the period at the range's end).
  bool aliases_at_range_end = true;
  // Where that moves a τ or a period, the backward check runs once more: an
  // effect chosen beside the drift at the grid's τ, or beside a cycle at
  // its first period, may now be redundant.
  bool backward_after_tau = true;
  // Parsimony between competing explanations of one structure: a cheaper
  // significant named candidate whose fitted contribution correlates with
  // the largest one's above `competing_corr` takes its place when its
  // information criterion ΔRSS/σ̂² − ln(n)·cost is better, cost = its
  // columns plus `searched_cost` for a parameter found by search (a period,
  // a time constant); false: the largest ΔRSS wins (before).
  bool parsimony_ic = true;
  double searched_cost = 2.0;
  double competing_corr = 0.9;
  // Before a smooth `unexplained` function is taken, combinations of up to
  // this many significant named candidates (greedy) compete with it on the
  // same criterion (1: no combinations).
  int combinations = 3;
  // Where the combination grown from the lead does not explain the
  // structure, it is grown again from the next significant parts of it (by
  // ΔRSS; not an arm offset, which carries the model's own table error), up
  // to this many leads in all; the best on the criterion of those that
  // explain it wins (1: from the lead alone; e.g. a drift that grows with
  // the position leads its own combination where an aliased cycle or a
  // scale came first).
  int combination_leads = 3;
  // A partner of a combination must add, beyond the others, this share of
  // the practical floor's sum of squares (n·min_effect_rms²·σ̂²; 0.5: an
  // RMS of 0.21 σ̂): a part of one structure may be smaller than an effect
  // of its own, but not so small that the model's own table error (a few
  // tenths of a µm, present in every data set) fills the place.
  double partner_floor_share = 0.5;
  // The linear parts of a coupling in the combination (a scale or
  // squareness of its direction along either of its axes) need only their
  // χ² as partners, not the floor: the catalogue's coupling is about the
  // travel's centre, a real one about any point, and the point's offset is
  // exactly those linear parts (a(s_i − c_i)(s_j − c_j) = a·s_i·s_j −
  // a·c_j·s_i − a·c_i·s_j + const); small as they may be, they belong to
  // the one structure.
  bool coupling_parts_at_chi2 = true;
  // And they join before any other partner (the best of them on the
  // criterion first): an arm offset, which carries the model's own table
  // error, otherwise takes a linear part's place.
  bool coupling_parts_first = true;
  // A cyclic partner (its period searched) must pass the whole practical
  // floor in what it adds, not `partner_floor_share` of it.
  bool cyclic_partner_full_floor = true;
  // And a cyclic lead of a structure must be significant beside its smooth
  // function too.
  bool cyclic_lead_beyond_smooth = true;
  // A cyclic partner of a combination must also be significant in what it
  // adds beside the smooth function it competes with (with the others): a
  // cycle is a function the smooth family does not resolve, so a real one
  // still adds; one whose period the scan chose because its columns, on
  // scattered points, happen to fit part of the smooth structure adds
  // nothing (false: tested against the combination's others only).
  bool cyclic_partner_beyond_smooth = true;
  // Where no named part of the smooth function's structure passes the
  // floors alone, the largest significant part leads a combination (false:
  // no combination then).
  bool lead_below_floor = true;
  // The structure's variables. Where no named part of the best smooth
  // function's variables explains its structure, a smooth function of the
  // positions only (not of the time) along the same direction that removes
  // at least this share of the best one's ΔRSS finds the same structure,
  // and the named parts of its variables are tried too
  // (Step::structure_vars): on a serpentine grid the time follows the rows
  // and the levels, so a function of (z, t) fits one of (y, z) nearly as
  // well. (With time too, on circles — where every variable is a function
  // of the angle — drifts at τ = 300 s stood for a scale: wrong names.)
  // 0: the best smooth function's variables only.
  double structure_near_share = 0.9;
  // The lead of a combination is `ambiguous` with a candidate that takes
  // its place in the combination without a significant loss, as every
  // partner is (false: the partners only; the lead then has only the
  // rivals it has alone).
  bool lead_rivals_in_combination = true;
  // …and not with a drift that costs more on the criterion (its time
  // constant searched) and removes less in the member's place (a drift
  // z·t→Y at τ 300 s, a squareness dY ∝ z but for the first minutes, in
  // place of the squareness): the criterion chose the cheaper form, as for
  // the rivals of a single pick. A costlier cycle stays a rival: on a
  // levelled axis its aliases are any function of the levels, the design's
  // ambiguity (false: any candidate within the margin).
  bool member_rivals_by_cost = true;
  // A drift that grows with a position (x·t→X) is named only where its
  // course in time adds, beside its static form (a scale or squareness),
  // more than the floor a name must pass (its χ² and the practical
  // floor); else the static form is the pick.
  bool drift_course_floor = true;
  // The smooth function's surplus. Where no named part of the best smooth
  // function's structure explains `name_ratio` of its ΔRSS, alone or in a
  // combination, a part still explains the structure when what the smooth
  // function adds beside it passes none of the smooth function's own floors
  // (its χ² and the practical floor): the rest is the noise a wide function
  // fits, or a structure below the floor (on a circle, the model's own
  // table error beside a small scale). The parts tried: smooth_surplus.hpp.
  // False: the share alone decides.
  bool smooth_surplus_test = true;
  // Where no named part of the smooth function's variables (nor of a near
  // one's) explains its structure, a thermal drift whose fitted contribution
  // the smooth function reproduces (≥ 0.9 of it) is a part of it too,
  // whatever its variables: on a circle every position is a function of the
  // angle and the pass, so x·t→X is one of (y, t) there. Not a drift whose
  // course is nearly done over the measurement (it stands for a static
  // term), nor a static term (on a serpentine walk z follows t, and a
  // squareness dX ∝ z joined a function of (x, t) by it: wrong names).
  // False: by the variables only.
  bool drift_parts_by_reproduction = true;
  // …at any time constant of its grid, not only the one its scan chose
  // against the residual alone (there a drift ∝ z whose course the scan
  // found nearly done at 300 s stands for a scale; at 3600 s, beside a
  // uniform drift, it is the drift ∝ z − z0 a smooth function of (x, t)
  // found). A combination with such a drift holds its lead to a partner's
  // floor too (structure.cpp, explains()). False: at its scanned time
  // constant only.
  bool drift_parts_at_other_tau = true;
  // The flexibility of a smooth `unexplained` function that wins a step is
  // chosen by the held-out SSE among these Legendre degrees (one variable;
  // per variable of a pair); empty: the candidates' fixed degree.
  std::vector<int> single_degrees{2, 3, 4, 6, 8, 10, 12};
  std::vector<int> pair_degrees{2, 3, 4, 5, 6};
  // After the forward steps, each named effect is tested again beside the
  // other named effects (backward_check.hpp); one the later steps made
  // redundant is dropped (false: every effect chosen stays).
  bool backward_check = true;
  // The revisit of the first step (docs/diagnosis.md, step 3): where the
  // forward path ends with a smooth `unexplained` function, the first
  // step's pick was a guess among near-equal ones (a drift's time constant
  // chosen while a second effect was still in the residual, a drift beside
  // a scale); up to `revisit_paths` paths are run again from each named
  // candidate of that step that removed at least `revisit_share` of what
  // the pick removed, and a path wins that is better on the criterion and
  // not worse held out (0: no revisit).
  int revisit_paths = 3;
  double revisit_share = 0.9;
  // …and also where the path ends with named effects only, from the first
  // step's near alternatives that cost less on the criterion than a first
  // pick with a searched parameter (a static effect in place of a drift);
  // such a path wins only where it also ends with no more effects with a
  // searched parameter than the kept one.
  bool revisit_searched_first = true;
  // A revisited path whose first pick is a drift that grows with a position
  // in place of its own static form (the kept first pick) wins only where
  // it removes more than the kept path by what the drift's course must add
  // beside that form at a step (drift_course_floor: one column's χ² and the
  // practical floor), unless the kept path ends with a smooth function and
  // the revisited one names that structure (false: the criterion and the
  // held-out SSE alone; on a serpentine walk z follows t, and a drift z·t→Z
  // at τ 600 s, a scale of Z but for the first minutes, took a scale's
  // place by the model's own error there).
  bool revisit_course_floor = true;
  // A revisited path wins only where its alternative takes the kept first
  // pick's place: one that names the kept pick after all (a cycle whose
  // period aliases a scale on a levelled axis, then the scale beside it)
  // wins only with no more effects with a searched parameter than the kept
  // path (false: any path better on the criterion and held out wins).
  bool revisit_alternative_replaces = true;
  // Where the path ends with a smooth function and its first pick is an arm
  // offset, the path without that arm offset is run too; it wins where it
  // is better on the criterion and not worse held out beyond the held-out
  // SSE's resolution (false, or revisit_paths 0: not run).
  bool revisit_without_arm_offset = true;
  // Optional: called at the start of each selection step (0-based), e.g. for
  // a progress bar.
  std::function<void(int step)> on_step;
};

struct SelectedTerm {
  Term term;  // with coef and stderr_ from the final joint fit
  // Share of the residual SS (after the datum) the term explains: its unique
  // part (what only it removes, given the others) plus its part of what the
  // effects explain only together (shared, split in proportion to each
  // term's overlap: what it removes alone minus its unique part). The
  // effects' explained_fraction add up to what they explain together.
  // Datum terms: their unique share of the raw residual.
  double explained_fraction = 0.0;
  double unique_fraction = 0.0;
  double shared_fraction = 0.0;
  // False when the standard uncertainty of the effect's value (its first
  // parameter) is not below the value: not a name (diagnosis.cpp).
  bool significant = true;
  std::vector<std::string> ambiguous_with;
  // A cycle named (its kind, axis and direction told by the design) whose
  // period is not: other periods that fit as well, in mm
  // (design_ambiguity.hpp).
  std::vector<double> other_periods_mm;
  // With ambiguous_with or other_periods_mm: what measurement would tell
  // them apart (separation.hpp, design_ambiguity.hpp).
  std::string separate_by;
  // An `unexplained` function only: the scale and squarenesses its fitted
  // structure contains (its projection on d_i ∝ s_a for each position
  // variable a, beside the datum; coef and stderr_ set), and the share of
  // the function's sum of squares they hold. Not names (linear_part.hpp).
  std::vector<Term> linear_parts;
  double linear_share = 0.0;
  // With the tables' uncertainty propagated (table_uncertainty.hpp): each
  // coefficient's standard uncertainty from the data alone and from the
  // tables (term.stderr_ then holds both combined), and the same for the
  // searched parameter (τ, period; −1: none). Empty: not propagated.
  std::vector<double> stderr_data, stderr_tables;
  double searched_stderr_data = -1.0, searched_stderr_tables = -1.0;
};

// Below this share of its function a linear part is neither shown nor used
// (the isotropic scale): beside named scales and squarenesses, which take
// the linear structure first, what is left of it is a rounding's worth.
inline constexpr double kLinearPartMinShare = 0.01;

struct SelectionResult {
  std::vector<SelectedTerm> terms;  // ordered by explained_fraction
  // The datum (offsets per set and direction, plate rotations): fitted with
  // the effects, reported apart; explained_fraction is its share of the raw
  // residual. The effects' explained_fraction is their share of what is
  // left after the datum.
  std::vector<SelectedTerm> datum;
  Eigen::VectorXd residual;         // after the final fit, per observation
  double sigma_um = 0.0;            // noise estimate per observation after the fit
  double cv_sse = 0.0;              // held-out SSE of the selected model
  double baseline_sse = 0.0;        // SSE of the residual without extension
  double datum_sse = 0.0;           // in-sample SSE after the datum alone
  double datum_cv_sse = 0.0;        // held-out SSE of the datum alone (the gain's baseline)
  double explained_together = 0.0;  // share of datum_sse the effects remove together
  std::vector<std::string> log;     // one line per step
};

// The forward selection from the datum, its backward check and final fit
// (docs/diagnosis.md, step 3), with the revisit of the first step where the
// path ends with a smooth function (SelectionOptions::revisit_paths).
SelectionResult select_effects(const Problem& problem, const CandidateSet& candidates,
                               const SelectionOptions& options);

// Whether the effects name this term (by its label; a combination's
// members are effects of their own).
bool names(const std::vector<SelectedTerm>& effects, const Term& term);

// Fold of every point (k-fold, shuffled by `seed`).
std::vector<int> point_folds(std::size_t points, int folds, std::uint64_t seed);

// The observation-level columns of a term (observations × columns).
Eigen::MatrixXd term_columns(const Problem& problem, const Term& term);

// Held-out SSE of a least-squares fit of the columns X to y over the folds.
double cross_validated_sse(const Problem& problem, const Eigen::MatrixXd& X,
                           const Eigen::VectorXd& y, const std::vector<int>& fold_of_point,
                           int folds);

}  // namespace abbe::diagnose
