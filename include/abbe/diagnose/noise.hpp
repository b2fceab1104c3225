#pragma once
// The measurement noise estimated apart from any model of the residual
// (docs/diagnosis.md, "Noise"): from the differences between repeated
// measurements of one point (same set, same nominal position, same
// direction of approach) when the data have enough of them, else from the
// second differences of neighbours in measurement order (same set, same
// measured direction, three points equally spaced on a line; a trend along
// the run cancels); "none" when the design has neither (scattered points).
// Robust (median absolute difference), so that a reversal step or a gross
// outlier does not inflate it.
#include <cstddef>
#include <string>

#include "abbe/diagnose/residuals.hpp"

namespace abbe::diagnose {

struct NoiseEstimate {
  double sigma_um = 0.0;  // per observation; 0 when the data allow no estimate
  std::string method;     // "repeated points", "neighbour differences" or "none"
  std::size_t pairs = 0;  // differences it rests on
};

NoiseEstimate estimate_noise(const Problem& problem);

}  // namespace abbe::diagnose
