#pragma once
// Test helpers for the identification tests: the dual-number paper's
// parameters and noise-free (phantom) observations of a chain.
#include "abbe/identify/parameter_identification.hpp"

namespace abbe::identify::testing {

// a, b, c (µm/m), f1 … h3 (µrad/m): sizes of a real machine.
inline ParamVector paper_parameters() {
  ParamVector p;
  p << 12.0, -8.0, 5.0, 30.0, -20.0, 15.0, -25.0, 18.0, -12.0, 22.0, -16.0, 9.0;
  return p;
}

// The deviation the chain with parameters p gives at `point`, observed exactly.
inline Observation exact_observation(const ChainExpansion& chain, const model::EvalPoint& point,
                                     const ParamVector& p) {
  Observation o;
  o.point = point;
  o.d_um = chain.deviation_um(point, p) + chain.squareness_um(point.p);
  return o;
}

}  // namespace abbe::identify::testing
