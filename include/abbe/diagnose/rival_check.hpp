#pragma once
// Rivals the data cannot reject (issue 16, "never a wrong name"). After the
// final fit, each named effect is put to a swap test: with everything else
// of the fit kept (the datum and the other effects), does another
// catalogue candidate in its place remove as much of the residual, or less
// by no more than a one-column χ² at `alpha` (σ̂² · χ²₁(α))? Then the data
// do not prefer the effect over that candidate, and the effect is reported
// `ambiguous` with it, never as a name. This is what the design's geometry
// decides case by case where no rule of design_ambiguity.hpp covers it:
// e.g. along the body diagonals a drift ∝ x·t in X and a drift ∝ y·t in Y
// differ only by the sign pattern of the four lines.
//
// Thermal-drift families are tried at every time constant of their grid;
// cyclic families only at the effect's own period (a period scan per swap
// would test hundreds of columns, and aliases are design_ambiguity's).
// Candidates whose columns (after the datum) hardly correlate with the
// effect's fitted contribution cannot stand in its place and are skipped
// before the exact test.
#include <string>
#include <vector>

#include "abbe/diagnose/candidates.hpp"
#include "abbe/diagnose/residuals.hpp"
#include "abbe/diagnose/selection.hpp"

namespace abbe::diagnose {

struct RivalOptions {
  bool enabled = true;
  double alpha = 0.01;
  // Exact test only for candidates whose best fit to the effect's
  // contribution reaches this |correlation| (after the datum).
  double prefilter_corr = 0.5;
  // The swap test is also made beside the fit's smooth `unexplained`
  // functions, where they leave the effect at least `smooth_keep_share` of
  // its columns' norm² beside the datum: a structure the named effects
  // leave (fitted by the smooth function) can favour one of two near-equal
  // names — e.g. a drift x·t with τ = 300 s over a scale of X, where part of
  // an off-centre coupling is left for the smooth function; beside it they
  // are judged on the effect's own shape. A rival in either test is a
  // rival (false: beside the datum and the named effects only).
  bool beside_smooth = true;
  double smooth_keep_share = 0.5;
  // A named drift in proportion to a position (x·t→X) and a rival of that
  // kind (y·t→Y) are each compared with their zero free, i.e. with the
  // uniform drift of the same direction and time constant beside them: the
  // catalogue's drift is about the machine's zero, a real one about where
  // the expansion starts, which no design knows. Along the body diagonals
  // y·t→Y about the zero fits a drift ∝ (x − x0)·t in X better than x·t→X
  // about the zero does.
  bool zero_free_drifts = true;
  // A uniform drift named beside such a drift, whose rival of another
  // direction was found with its zero free, is that drift's zero as much:
  // the pair is swapped for the rival with its zero free and the uniform
  // drift moved to the rival's direction; where that removes as much, the
  // moved drift is an alternative ("thermal_drift t→X (τ …) (the zero of
  // thermal_drift x·t→X (τ …))").
  bool uniform_drift_as_zero = true;
  // And the pair is swapped for every catalogue drift in proportion to a
  // position of another direction, not only the rivals found: a rival that
  // needs its own zero to stand in is not found alone (the named pair's
  // zero is in the uniform drift), and an effect design_ambiguity marked is
  // not put to the rival test. The proportional drift then gets that drift
  // as its alternative too ("thermal_drift x·t→X (τ …) (with its zero,
  // thermal_drift t→X (τ …))"). false: the rivals found only.
  bool zero_pair_every_direction = true;
  // An arm offset (the model's own angular tables times an unknown arm)
  // carries those tables' error, which every residual holds too (the real
  // arms times the same error): on top of what it shares with a rival it
  // fits part of that error, by more than one column's χ² on a large data
  // set. It is preferred over a rival only where it removes more by this
  // share of the practical floor's sum of squares (n·min_effect_rms²·σ̂²,
  // what an effect must remove to be named at all; half of it was not
  // enough on a machine whose model error is twice the noise); 0: by one
  // column's χ² as every other effect.
  double arm_offset_floor_share = 1.0;
  // An arm offset named beside a coupling is swapped, with that coupling
  // with its centre free (its linear parts beside it), for every catalogue
  // coupling with its centre free: a coupling off its travel centre holds a
  // scale or squareness along each of its axes, which an arm offset whose
  // angular table is near linear fits. Where one removes as much (by the
  // arm offset's margin), it is the arm offset's alternative ("coupling
  // x·z→X off its travel centre (its linear parts …)"). false: not tested.
  bool arm_offset_as_coupling_centre = true;
  // And an arm offset named where no coupling is: swapped alone for every
  // catalogue coupling with its centre free, which must remove as much and
  // ln(n)·σ̂² for each of its two extra columns (along the body diagonals an
  // off-centre coupling is a parabola plus slopes along each line, and the
  // model's angular table times an arm fits that as one column). false: only
  // beside a named coupling.
  bool arm_offset_alone_as_coupling = true;
};

// Marks the effects (fitted, with coef) the data do not prefer over another
// candidate of `catalogue`; `datum`: the fitted datum terms. A candidate that
// costs more than the effect (columns, plus `searched_cost` for a period or
// time constant found by search: SelectionOptions::searched_cost) is not a
// rival, as in the selection's parsimony rule. Returns one log line per
// rival found. `min_effect_rms`: the practical floor
// (SelectionOptions::min_effect_rms; 0: none) for arm_offset_floor_share.
std::vector<std::string> mark_unrejected_rivals(const Problem& problem,
                                                const std::vector<SelectedTerm>& datum,
                                                std::vector<SelectedTerm>& effects,
                                                const CandidateSet& catalogue, double searched_cost,
                                                const RivalOptions& options,
                                                double min_effect_rms = 0.0);

}  // namespace abbe::diagnose
