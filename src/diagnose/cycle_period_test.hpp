#pragma once
// The cycle period test of the design checks (docs/diagnosis.md, 4b): a
// cycle on a levelled axis is known by its samples at the levels only.
#include <cstddef>
#include <string>
#include <vector>

#include "abbe/diagnose/design_ambiguity.hpp"
#include "level_span.hpp"

namespace abbe::diagnose::design {

// The datum and every effect fitted together: its span and residual.
struct WholeFit {
  Mat Q;
  Vec r;
};

// The cycle period test of effect e (a cycle of axis j in direction i): the
// positions of s_j where direction i is measured, when they are levels (a
// laser line's targets, a grid's levels). A cycle there is known by its
// samples at the levels only: its period is the data's where no other period
// of the catalogue's range (away from its own main lobe, 1/span in
// frequency) removes as much in its place beside everything else of the fit
// (one column's χ² at `swap_alpha`); and it must remove most of what any
// function of the levels removes in its place (`cycle_share_of_levels`),
// else it is a piece of a structure that is not a cycle (e.g. the model's
// own table error at the levels), its period the one of many that fit best.
// Where the data tell the cycle's kind, a period another period matches
// stays its unresolved period (SelectedTerm::other_periods_mm;
// DesignAmbiguityOptions period_only_*); elsewhere its other periods become
// alternatives. `whole`: the datum and every effect fitted together.
void test_cycle_period(const Problem& pb, const Mat& D, const std::vector<Mat>& cols, std::size_t e,
                       std::vector<SelectedTerm>& effects, const DesignAmbiguityOptions& o,
                       double min_period_mm, const WholeFit* whole, std::vector<std::string>& log);

}  // namespace abbe::diagnose::design
