#pragma once
// One searched parameter per chosen term refined in the final fit, each term
// beside every other named term (the smooth `unexplained` ones aside): a
// drift's τ (time_constant.hpp) and a cycle's period (chosen_periods.hpp).
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "abbe/diagnose/residuals.hpp"
#include "abbe/diagnose/term.hpp"
#include "candidate_fit.hpp"

namespace abbe::diagnose::selection {

struct FinalRefit {
  // Which chosen terms are refined.
  std::function<bool(const Term&)> applies;
  // The term at its best parameter beside span(Q) (r ⟂ Q), and what it
  // removes there; the term unchanged when there is nothing to search.
  std::function<std::pair<Term, double>(const Term&, const Mat& Q, const Vec& r)> refine;
  // The log line of a moved term: before, after, what each removes.
  std::function<std::string(const Term&, const Term&, double, double)> describe;
};

// Each chosen term `applies` takes in turn: refined beside the others and
// kept where it removes more; its columns in X (the chosen terms' columns
// side by side, in order) are replaced and a line is logged. Returns
// whether any term moved (false, and nothing done, when X is not the
// chosen terms' columns).
bool refine_each_beside_others(const Problem& pb, Mat& X, const Vec& y, std::vector<Term>& chosen,
                               const FinalRefit& how, std::vector<std::string>& log);

}  // namespace abbe::diagnose::selection
