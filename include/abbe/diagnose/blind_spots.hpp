#pragma once
// What the measurement design cannot test at all (issue 16, "identifiability
// from the design": a single plane cannot see Z effects, a line sees only
// its direction). Before any fit, from the data's layout alone: the parts of
// the effect catalogue that have no candidate in these data, each with why
// and the measurement that would add it —
//  - a direction not measured (a plate without dz): no effect in it;
//  - no time (t constant): no drift in time;
//  - an axis at one position (one plane): nothing that varies with it;
//  - an axis never approached from both sides, or no approach direction in
//    the data (vx vy vz 0 or missing): no reversal of it;
//  - a direction measured only where an axis stands still (a laser line
//    along X measures d_x at one y and z): no d_i as a function of s_j;
//  - an axis on a few regular levels (design_ambiguity.hpp): no cycle of it
//    shorter than two level spacings;
//  - an axis over a short travel (a 50 mm ballbar circle spans 100 mm): no
//    cycle of it longer than half its span (CandidateOptions::
//    max_period_span_share), which it does not hold twice.
// Reported as such (text, JSON `blind_spots`, HTML), never as an effect.
#include <string>
#include <vector>

#include "abbe/diagnose/design_ambiguity.hpp"
#include "abbe/diagnose/residuals.hpp"

namespace abbe::diagnose {

struct BlindSpot {
  std::string what;     // the part of the catalogue, e.g. "a drift in time (thermal_drift)"
  std::string reason;   // why these data cannot test it
  std::string measure;  // what would add it
};

// `min_period_mm`, `max_period_mm`, `max_period_span_share`: the
// catalogue's cycles (CandidateOptions).
std::vector<BlindSpot> blind_spots(const Problem& problem, const DesignAmbiguityOptions& design,
                                   double min_period_mm, double max_period_mm,
                                   double max_period_span_share = 0.5);

}  // namespace abbe::diagnose
