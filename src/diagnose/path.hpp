#pragma once
// One forward path of the selection (docs/diagnosis.md, step 3): the steps,
// the backward check and the final fit, from the datum on — optionally with
// its first step's pick given (the revisit of the first step, revisit.hpp).
#include <optional>
#include <vector>

#include "abbe/diagnose/candidates.hpp"
#include "abbe/diagnose/selection.hpp"

namespace abbe::diagnose::selection {

// What the revisit needs of a path beyond its SelectionResult (whose terms
// give its cost and columns, and cv_sse its held-out SSE).
struct PathSummary {
  double rss = 0.0;  // the joint fit's residual SS (before the final fit's stages)
  // The first step's pick when it is a single named effect (not a smooth
  // function, a combination or nothing).
  std::optional<Term> first;
  // Not forced: the first step's other named candidates that remove at least
  // SelectionOptions::revisit_share of what the pick removes (significant
  // alone), and the pick's own family at its other time constants, largest
  // first.
  std::vector<Term> first_alternatives;
  // Where the pick has a searched parameter: the near alternatives (before
  // the cut to revisit_paths) that cost less on the criterion, at most
  // revisit_paths (SelectionOptions::revisit_searched_first).
  std::vector<Term> first_cheaper_alternatives;
};

// forced_first: the first step takes this term (no alternatives are sought).
SelectionResult select_path(const Problem& problem, const CandidateSet& candidates,
                            const SelectionOptions& options, const Term* forced_first,
                            PathSummary& summary);

// A term with a parameter found by search (a cycle's period, a drift's time
// constant).
bool has_searched_parameter(const Term& t);

// A term's cost on the information criterion: its columns, plus
// `searched_cost` for a parameter found by search (a period, a time constant).
double criterion_cost(const Term& t, double searched_cost);

}  // namespace abbe::diagnose::selection
