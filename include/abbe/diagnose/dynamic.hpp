#pragma once
// The dynamic signatures of a circular test (ISO 230-4, ballbar) that the
// quasi-static diagnosis does not explain and never names: servo mismatch
// (unequal gains of the two axes of the plane: an ellipse at 45° that turns
// with the direction of travel) and reversal spikes (short peaks just after
// an axis reverses at a quadrant point). They are looked for in the residual
// of the fit of each circle measured both ways and reported as dynamic, out
// of the diagnosis' scope (docs/diagnosis.md, "Ballbar").
#include <Eigen/Core>
#include <string>
#include <vector>

#include "abbe/diagnose/residuals.hpp"

namespace abbe::diagnose {

struct DynamicFinding {
  std::string kind;  // "servo_mismatch" or "reversal_spikes"
  std::string set;
  double amplitude_um = 0.0;  // ellipse half-difference, or the mean spike height
  double z = 0.0;             // the signature over its standard error
};

struct CircleCheck {
  std::vector<std::string> circles;  // sets measured as circles (dn along the radius)
  std::vector<DynamicFinding> findings;
};

// `residual`: per observation after the fit; `sigma`: its noise (µm).
CircleCheck check_circles(const Problem& problem, const Eigen::VectorXd& residual, double sigma);

}  // namespace abbe::diagnose
