#pragma once
// The structure a smooth function finds, explained by catalogue effects
// (docs/diagnosis.md, step 3): the named part of it that leads and a
// combination of catalogue effects that explains it whole at a lower cost.
#include <deque>
#include <set>
#include <string>
#include <vector>

#include "step.hpp"

namespace abbe::diagnose::selection {

// What the structure search decided.
struct StructureChoice {
  const Score* lead = nullptr;    // the named part of the structure that leads
  bool lead_explains = false;     // the lead alone explains the structure
  bool combination_wins = false;  // the lead with `partners` explains it
  std::vector<const Score*> partners;
  double d_partners = 0.0;  // ΔRSS of the whole combination
  // Per member, the lead first: what may stand in its place in the
  // combination (the lead's only with lead_rivals_in_combination).
  std::vector<std::vector<Term>> member_rivals;
  // Drifts re-scanned at other time constants for the combination (a
  // partner may point to one): kept for the step.
  std::deque<Cached> rescanned;
  std::deque<Score> rescanned_scores;
  // Of those, the drifts not a part of the structure at their own time
  // constant (drift_parts_at_other_tau).
  std::set<const Score*> at_other_tau;
};

// Where the smooth function explains more than the best named candidate
// can: its structure is explained from the best named candidate that is a
// part of it (or, where none passes the floors alone, the largest
// significant part: e.g. a coupling whose linear parts take half of it),
// alone or in a combination (lead_below_floor); a combination that does not
// explain it is grown again from the next significant parts
// (combination_leads). `out` must outlive the step
// (partners may point into its re-scanned drifts).
void explain_structure(const Step& s, const Score* best_named, int step, StructureChoice& out,
                       std::vector<std::string>& log);

}  // namespace abbe::diagnose::selection
