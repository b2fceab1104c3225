#pragma once
// The backward check of the forward selection (docs/diagnosis.md, step 3):
// a named effect chosen early may be made redundant by named effects chosen
// after it — e.g. a cycle whose aliased wave, on the regular levels of a
// grid, took a scale's line and part of a reversal before the reversal was
// in the fit, then the scale came in at a later step. Each named effect is
// tested again, given the datum and every other named effect, at the
// forward step's significance level (the χ² test alone, not the practical
// floor: a combination's partner may be below the floor and still needed).
// Smooth `unexplained` functions are left out of the test: a Legendre
// family holds a scale's line and would make it look redundant.
#include <cstddef>
#include <optional>
#include <vector>

#include "abbe/diagnose/term.hpp"
#include "candidate_fit.hpp"

namespace abbe::diagnose::selection {

struct Redundant {
  std::size_t index = 0;          // in `chosen`
  Eigen::Index first_column = 0;  // its first column in X
  double delta_rss = 0.0;         // what it removes given the others, µm²
  double threshold = 0.0;         // σ̂²·χ²_k(α), µm²
};

// X: the chosen terms' columns side by side, in the order of `chosen` (its
// first n_datum terms the datum); Qd: the datum's orthonormal span; y: the
// data; s2: the full fit's residual variance; alpha: the test level per
// term. Returns the named effect that adds least beside the others, when
// that is below its test; nothing when every named effect holds.
std::optional<Redundant> least_needed_named(const Mat& X, const Mat& Qd, const Vec& y,
                                            const std::vector<Term>& chosen, std::size_t n_datum,
                                            double s2, double alpha);

}  // namespace abbe::diagnose::selection
