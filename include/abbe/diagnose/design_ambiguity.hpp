#pragma once
// What the measurement design cannot tell apart among the selected effects
// (issue 16, "identifiability from the design"). Checked after the final
// fit; an effect found ambiguous gets its alternatives (`ambiguous_with`)
// and what to measure to separate them (`separate_by`), never a name:
//  - Levelled axes. An axis the design samples at a few discrete levels,
//    spaced at least twice the shortest catalogue period apart (a regular
//    grid, a plate's rows, targets along a line), aliases every shorter
//    period: a pitch error sampled there is an arbitrary function of the
//    levels. When the selection explains one structure along such an axis
//    with a cycle of that axis (or a smooth function of it alone) AND other
//    effects that are functions of the same levels in the same direction (a
//    scale, a squareness, an arm offset, a reversal constant per row), the
//    split between them is the aliasing's, not the machine's: all of them
//    are ambiguous ("sample that axis at irregular spacing"). Where time
//    is mostly a function of such an axis's levels — the design walks the
//    levels in order, e.g. a grid measured in one pass — the data decide by
//    a swap test (the effect and a stand-in each added to everything else
//    of the fit; the stand-in wins when it removes as much, or less by no
//    more than a one-column χ² at `swap_alpha`): a drift in time is
//    ambiguous with any function of the levels in its direction or with the
//    static terms it becomes when t follows s_j, and a static effect of the
//    levels with a drift in its direction ("measure again in another order
//    or after a pause"). On at most `few_levels` levels a cycle of the axis
//    fits any values of the levels: an effect that is a function of them is
//    a pitch error as much ("measure that axis at more levels").
//    Where time follows an axis that is not levelled (a raster
//    toolpath's rows), the same swap tests run on bins of that axis: a
//    coupling w·j is a drift ∝ s_w·t as much, and a drift a scale,
//    squareness or coupling of j, unless the data prefer it.
//  - A reversal that grows along its travel. Where the design drives the
//    axis one way almost everywhere, sign(v_j)·s_j and s_j coincide: an
//    effect linear in s_j beside a reversal of that axis (a scale, a drift
//    ∝ s_j·t, ...) may be the reversal's growth: when, given everything
//    else, the growth column sign(v_j)·(s_j − mid) removes as much as the
//    effect, or less by no more than a one-column χ² at `swap_alpha`
//    (the data do not prefer the effect), the effect is ambiguous ("drive
//    the axis both ways over its whole travel").
//  - A growing reversal's jump. Where every axis reverses at once (a line
//    through the volume driven there and back: the body diagonals), each
//    axis's reversal jump is the same step along the line: the growth tells
//    the axis whose reversal grows, the jump does not. Where the data hold
//    a jump beside the growth (it adds more than the margin to everything
//    else) and the reversal of another axis, its jump in place of the
//    growing one's beside the same growth, removes as much given
//    everything else (or less by no more than a one-column χ² at
//    `swap_alpha`), that reversal is an alternative of the jump ("reversal
//    Z→Z (its jump)"; "measure each axis's reversal on its own").
#include <array>
#include <string>
#include <vector>

#include "abbe/diagnose/residuals.hpp"
#include "abbe/diagnose/selection.hpp"

namespace abbe::diagnose {

struct DesignAmbiguityOptions {
  bool levelled_axes = true;
  // An axis with at most this many distinct positions counts as levelled
  // (when its levels are also ≥ 2 × the shortest period apart).
  std::size_t max_levels = 40;
  // A term counts as a function of the levels when at most this share of its
  // columns' sum of squares lies outside their span (an arm offset ε_j×Δ is
  // one up to the tables' direction-dependent part)
  double level_share_left = 0.1;
  // and, beside the datum (the per-set offsets the fit always carries), at
  // most this share: a drift measured long after the machine started is
  // mostly its mean over the measurement, an offset that the level
  // indicators hold as well as the datum does. Along the body diagonals in
  // five runs a drift t→X kept 7 % of its raw sum of squares outside the
  // 30 levels of z, and all of it beside the datum; a drift linear in t on
  // a grid walked once over 3 levels keeps 3 % and 11 %. 1: not checked.
  double level_share_left_beside_datum = 0.5;
  // On this many levels or fewer a cycle of the axis fits any values of
  // the levels (period, phase and amplitude for L − 1 values).
  std::size_t few_levels = 4;
  // Time mostly follows the levels (a drift and a static effect of the
  // levels are tested against each other) when at most this share of its
  // variance is within levels (a one-pass walk of 3 levels leaves 1/9).
  double time_share_left = 0.2;
  // Time may follow an axis the design does not level too (a raster
  // toolpath: rows along X stepping in Y, a contour at the end). There a
  // static effect of s_j (a scale or squareness of j, a coupling with j)
  // is swap-tested against the drift it becomes when t follows s_j
  // (uniform, or ∝ s_w·t for a coupling w·j), and a drift against those
  // static terms (time_follows_unlevelled), where less than
  // `time_share_left_unlevelled` of the time's variance is left within
  // `time_bins` bins of s_j of equal counts (more than half of it is a
  // function of s_j; a raster of 19 rows with a contour at the end leaves
  // 0.21).
  bool time_follows_unlevelled = true;
  std::size_t time_bins = 20;
  double time_share_left_unlevelled = 0.5;
  // The drift's time constants tried in place of a static effect there (0:
  // linear in t); empty: the candidates' default grid (CandidateOptions;
  // diagnose_problem gives its own candidates' grid).
  std::vector<double> tau_s;
  bool growing_reversal = true;
  // A growing reversal's jump tested against the other axes' reversals
  // (the jump's axis, not the growth's).
  bool reversal_jump = true;
  // A cycle of a levelled axis is tested against a cycle at every other
  // period of the catalogue's range in its place: its period is the data's
  // only where none removes as much.
  bool cycle_period_test = true;
  // …and it must remove at least this share of what any function of the
  // levels removes in its place (as a named kind of the smooth function's,
  // SelectionOptions::name_ratio).
  double cycle_share_of_levels = 0.7;
  // The margin another period must come within is one column's χ² times
  // the noise of a function of the levels: the larger of σ̂² and what the
  // levels hold beyond the whole fit per degree of freedom (the model's own
  // error at each target repeats in every run, so the levels' values scatter
  // more than single readings; false: σ̂² alone).
  bool level_noise_margin = true;
  // And with each level left out in turn: a period that another period
  // matches (within the margin) once one level is gone rests on that level
  // and is not named.
  bool level_out_test = true;
  // A cycle whose period another period matches (either test above) is
  // still a cycle of its axis where the design tells its kind: on at least
  // `period_only_min_levels` levels it removes at least `period_only_share`
  // of what any function of the levels removes in its place, and more than
  // a smooth function of the axis there (a polynomial of degree 0 to
  // `period_only_smooth_degree`, at most levels − 3) by the margin, and
  // its axis does not move in lockstep with another on every line (a body
  // diagonal: a cycle of one axis is a cycle of the other there). Then it
  // is named with its period unresolved (SelectedTerm::other_periods_mm),
  // not `ambiguous`. (A cycle at a searched frequency holds 0.95 of noise
  // on L levels — L − 1 values beside the offset, two of them its columns —
  // with a chance of about 0.05^((L − 3)/2) per independent frequency: 3·10⁻³
  // for L = 8, 6·10⁻⁶ for L = 11, times the few hundred frequencies of the
  // catalogue's range. The selection's own aliases of a cycle are kept as
  // its other periods only where this tells its kind.)
  std::size_t period_only_min_levels = 11;
  double period_only_share = 0.95;
  int period_only_smooth_degree = 6;
  // Without a level, other periods are sought near this many of the largest
  // peaks of the scan with every level (each refined as in the full scan).
  std::size_t level_out_peaks = 8;
  // The longest period the test tries (0: the candidates' default;
  // diagnose_problem gives its own candidates' max_period_mm).
  double max_period_mm = 0.0;
  // The swap tests' level: one column's χ² at this α (the growth of a
  // reversal, a drift against the static terms, and back).
  double swap_alpha = 0.01;
};

// The levels of each axis when the design samples it at few levels spaced
// so that periods down to `min_period_mm` (the catalogue's shortest) alias;
// empty for the other axes.
std::array<std::vector<double>, 3> levelled_axes(const Problem& problem,
                                                 const DesignAmbiguityOptions& options,
                                                 double min_period_mm);

// A cycle's other periods (SelectedTerm::other_periods_mm) moved to its
// alternatives (`ambiguous_with`, as the same cycle at those periods): its
// period not resolved, and now not its name either.
void periods_as_alternatives(SelectedTerm& effect);

// Marks the effects (fitted, with coef) the design cannot tell apart;
// `datum`: the fitted datum terms. Returns one log line per marked effect.
std::vector<std::string> mark_design_ambiguities(const Problem& problem,
                                                 const std::vector<SelectedTerm>& datum,
                                                 std::vector<SelectedTerm>& effects,
                                                 const DesignAmbiguityOptions& options,
                                                 double min_period_mm);

}  // namespace abbe::diagnose
