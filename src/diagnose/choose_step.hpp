#pragma once
// One step of a forward path (docs/diagnosis.md, step 3): the best named
// candidate (its scanned parameters found first), the best smooth function,
// and whether a named part of its structure, alone or with partners,
// explains it at a lower cost. What a path keeps from step to step (the
// candidates' cached columns, the smooth families' Gram matrices, the
// floors' caches) is a PathState.
#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "abbe/diagnose/candidates.hpp"
#include "abbe/diagnose/selection.hpp"
#include "candidate_fit.hpp"
#include "path.hpp"

namespace abbe::diagnose::selection {

// A smooth family with its point-level Gram matrix per measured direction.
struct GenericFamily {
  Term term;
  std::array<Mat, 3> G;
};

struct PathState {
  // Q: the datum's span; named candidates without a searched parameter,
  // their columns once.
  PathState(const Problem& pb, const CandidateSet& cs, const SelectionOptions& o, const Mat& Q);

  std::vector<Cached> named;
  std::vector<GenericFamily> generic;
  std::vector<std::size_t> set_of;  // per point: its set's index in pb.sets
  double tests_named = 1.0, tests_generic = 1.0;
  std::size_t stride = 1;  // the period scan's subsample
  double lambda = 0.0;     // the practical floor's non-centrality, n·min_effect_rms²
  std::map<std::string, std::array<double, 3>> share_cache;  // by label, per direction
  // Per axis: its positions are at most o.alias_levels distinct levels.
  std::array<bool, 3> levelled{};
  // The cycles chosen on this path so far (ScanInput::chosen_cycles).
  std::vector<Term> cycles;

  // The practical floor for k columns, in units of σ̂² (min_effect_test).
  double practical(int k, const SelectionOptions& o);
  // After a step: the named candidates' projections on the span's new
  // columns Qnew, the picked ones (by label) removed, the picked cycles
  // added to `cycles`.
  void advance(const Mat& Qnew, const std::vector<Term>& picked);

 private:
  std::array<double, 64> practical_cache_{};  // by column count
};

// What a step takes: its pick (a named effect, possibly with the partners
// of a winning combination, or a smooth function), each named one's rivals.
struct StepChoice {
  Term pick;
  Mat C;  // the pick's columns and its partners'
  double d = 0.0;
  Alternatives amb;
  std::string separation;
  std::vector<Term> partners;
  std::vector<Alternatives> partner_amb;
  std::vector<std::string> partner_separation;
  // Where a smooth function is the pick: the best significant named
  // candidate, which takes its place if the function fails the held-out
  // check.
  std::optional<Term> fallback;
  Mat fallback_C;
  double fallback_d = 0.0;
};

// The step's choice on the residual r (⟂ the span Q). False when no
// candidate passes the floors (logged). first (the first step): its
// alternatives filled with the pick's near alternatives for the revisit.
bool choose_step(const Problem& pb, const CandidateSet& cs, const SelectionOptions& o,
                 PathState& ps, const Mat& Q, const Vec& r, int step, StepChoice& out,
                 std::vector<std::string>& log, PathSummary* first);

}  // namespace abbe::diagnose::selection
