#pragma once
// The chosen cycles' periods once more in the final fit, each beside every
// other named term. A cycle's period is refined when it is chosen, beside
// what was chosen before it; a pitch error's harmonic, chosen after, moves
// the fundamental's least-squares period, and over a short travel (a 50 mm
// ballbar circle spans 100 mm) the fundamental at its first period drifts
// in phase across the data: a scale or a third cycle then takes up what it
// left. The backward check that follows (SelectionOptions::
// backward_after_tau) drops what the refined cycles make redundant.
#include <string>
#include <vector>

#include "abbe/diagnose/candidates.hpp"
#include "abbe/diagnose/residuals.hpp"
#include "abbe/diagnose/term.hpp"
#include "candidate_fit.hpp"

namespace abbe::diagnose::selection {

// Each chosen cyclic term in turn: the frequency within ±half the
// resolution 1/span of its axis (span: the measured travel; beyond that
// it would be another cycle), and within its family's frequencies in `cs`,
// that removes most beside the other named
// terms (every chosen term but the smooth ones), by Brent's method. Kept
// where it removes more; the term's columns in X (the chosen terms'
// columns side by side, in order) are replaced. One log line per moved
// period. Returns whether any period moved.
bool refine_chosen_periods(const Problem& pb, const CandidateSet& cs, Mat& X, const Vec& y,
                           std::vector<Term>& chosen, std::vector<std::string>& log);

}  // namespace abbe::diagnose::selection
