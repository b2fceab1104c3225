#pragma once
// The selection's final joint fit and its attribution: the chosen terms'
// coefficients with their standard uncertainties (and the searched
// parameters': a cycle's period, a drift's τ), in two stages (the named
// effects with the datum, then the smooth remainder on what they leave),
// and each effect's share of the residual, unique and shared, adding up to
// what the effects explain together.
#include <string>
#include <vector>

#include "abbe/diagnose/selection.hpp"
#include "candidate_fit.hpp"

namespace abbe::diagnose::selection {

// What the selection chose, in order (the datum's terms first), with each
// term's alternatives and what would separate them.
struct Chosen {
  const std::vector<Term>& terms;
  const std::vector<Alternatives>& ambiguous;
  const std::vector<std::string>& separations;
  std::size_t n_datum = 0;
};

// X: the chosen terms' columns side by side; Qd: the datum's orthonormal
// span. Fills res.terms, res.datum, res.residual, res.sigma_um and
// res.explained_together (res.baseline_sse and res.datum_sse are read).
// pb: the problem the columns came from (for the searched parameters'
// uncertainties, searched_uncertainty.hpp).
void fit_chosen(const Problem& pb, const Mat& X, const Vec& y, const Mat& Qd, const Chosen& chosen,
                SelectionResult& res);

}  // namespace abbe::diagnose::selection
