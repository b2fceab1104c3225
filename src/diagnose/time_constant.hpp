#pragma once
// A drift's time constant between the values of the candidate grid. The
// selection scans τ on CandidateOptions::tau_s (steps of 1.3–2×). At the
// grid's value a drift leaves a part of itself in the residual — within a
// run time follows the position, and that part is picked up as a scale or
// a smooth function beside the drift — and the reported τ with its standard
// uncertainty (searched_uncertainty.hpp, the fit's curvature in τ) lies
// many uncertainties from the τ the data fit best (a drift of τ 1500 s
// reported as 1200 ± 41 s).
#include <string>
#include <utility>
#include <vector>

#include "abbe/diagnose/residuals.hpp"
#include "abbe/diagnose/term.hpp"
#include "candidate_fit.hpp"

namespace abbe::diagnose::selection {

// The τ in [lo, hi] at which `drift` (its other fields as given) removes
// most of r beside span(Q) (r ⟂ Q): Brent's method on ln τ. Returns τ and
// what the drift removes there.
std::pair<double, double> best_time_constant(const Problem& pb, const Mat& Q, const Vec& r,
                                             const Term& drift, double lo, double hi);

// A chosen drift of the scan (c: τ > 0 of `grid`) refined between the
// grid's neighbours of its τ on the exact ΔRSS beside span(Q) (r ⟂ Q;
// SelectionOptions::exact_tau). c's term, columns and products are
// replaced where the refined τ removes more. Returns what c removes then.
double refine_tau_exactly(const Problem& pb, const Mat& Q, const Vec& r,
                          const std::vector<double>& grid, Cached& c);

// In the final fit, each chosen thermal_drift with τ > 0 in turn: the τ that
// removes most beside the other named terms (the named stage of
// final_fit.hpp: every chosen term but the smooth ones), within [τ/2, 2τ]
// (SelectionOptions::refine_tau). Kept where it removes more; the term's
// columns in X (the chosen terms' columns side by side, in order) are
// replaced with it. One line per refined drift is appended to `log`.
// Returns whether any τ moved.
bool refine_time_constants(const Problem& pb, Mat& X, const Vec& y, std::vector<Term>& chosen,
                           std::vector<std::string>& log);

}  // namespace abbe::diagnose::selection
