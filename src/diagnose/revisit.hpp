#pragma once
// The revisit of the first step (docs/diagnosis.md, step 3). The forward
// selection takes, at each step, what removes most; its first pick is made
// while every other effect is still in the residual. Where two named
// candidates remove nearly as much (a drift at τ 900 s or at 1 800 s, a
// drift that grows with x or a scale of X), the one that wins may be the one
// that takes part of the second effect's structure, which a smooth
// function then fits at a later step. Where a path ends with a smooth
// `unexplained` function, the paths from the first step's near
// alternatives are run too; one that is better on the information
// criterion (RSS + σ̂²·ln(n)·cost, σ̂² the smaller residual variance of the
// two) and not worse held out replaces it. Where a path ends with named
// effects only and its first pick has a searched parameter (a drift z·t→Y
// that took a squareness dY ∝ z and part of a drift of Y), the paths from
// the near alternatives that cost less are run (revisit_searched_first),
// and one wins only where it also ends with no more searched effects.
// A path that names the kept first pick after all (its alternative joined
// the pick instead of taking its place: a cycle aliasing a scale on a
// levelled axis, the scale beside it) is held to that condition too
// (revisit_alternative_replaces). Where a path that ends with a smooth
// function picked an arm offset first, the path without it is run too
// (revisit_without_arm_offset; held out within the comparison's
// resolution, 2·σ̂·‖δ‖).
#include <vector>

#include "abbe/diagnose/candidates.hpp"
#include "abbe/diagnose/selection.hpp"
#include "candidate_fit.hpp"
#include "step.hpp"

namespace abbe::diagnose::selection {

// The first step's near alternatives to `pick` (PathSummary::first_alternatives):
// the scored candidates above their floors that remove at least
// o.revisit_share of d_pick, and a drift's own family at its other time
// constants, largest ΔRSS first, at most o.revisit_paths (out); and, where
// the pick has a searched parameter, those among them (before that cut)
// that cost less on the criterion, at most o.revisit_paths (cheaper).
// Q, r: the span and residual of the step (the datum's).
void first_step_alternatives(const Problem& pb, const CandidateSet& cs, const SelectionOptions& o,
                             const Mat& Q, const Vec& r, const std::vector<Score>& scores,
                             const Term& pick, double d_pick, std::vector<Term>& out,
                             std::vector<Term>& cheaper);

}  // namespace abbe::diagnose::selection
