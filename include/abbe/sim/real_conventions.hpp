#pragma once
// The virtual laser campaign as real laser software reports it (docs/models.md,
// "Reference conventions and the part"): linear positioning zeroed at a
// reference target, straightness about its least-squares reference line (the
// slope removed), angles relative to the reference target, the squareness
// that goes with those references, and reflector positions recorded with an
// error of a few mm.
#include <cstdint>

#include "abbe/sim/laser_campaign.hpp"
#include "abbe/sim/truth_generator.hpp"

namespace abbe::sim {

struct RealConventions {
  bool zero_positioning = true;           // EXX, EYY, EZZ: 0 at the reference target
  bool remove_straightness_slope = true;  // and its constant: the reference line
  bool relative_angles = true;            // EA…EC: 0 at the reference target
  double reflector_sigma_mm = 0.0;  // recorded reflector points off by N(0, σ) per coordinate
  std::uint64_t seed = 1;           // of the reflector errors
};

// What was removed, per axis j and component c: a + b·s (µm or µrad; b per mm)
// subtracted from every reading of the component; and the change of the
// squareness (µrad) that keeps the prediction of the part the same.
struct ConventionRecord {
  double a[3][6] = {};
  double b[3][6] = {};
  Squareness squareness_change;
};

// Rewrites the table, the runs and the squareness of `result` and, for the
// reflector error, the recorded points of `machine.campaign` (the truth is
// untouched). The reference target of an axis is its first target. The
// squareness change is the one that turns the change of the prediction into
// a rigid motion (chain of `machine.truth`).
ConventionRecord apply_real_conventions(GeneratedMachine& machine, CampaignResult& result,
                                        const RealConventions& conventions);

}  // namespace abbe::sim
