#pragma once
// Scales of several axes named together that agree within their standard
// uncertainties are consistent with one isotropic scale: the signature of a
// temperature difference (of the part or artefact from 20 °C, or between
// making a part and measuring it), where a laser compensation error differs
// per axis (docs/diagnosis.md, "Isotropic scale"). Read from the final fit;
// the scales' correlation in the joint fit is neglected.
#include <vector>

#include "abbe/diagnose/selection.hpp"

namespace abbe::diagnose {

// Linear expansion coefficients for the temperature the scale corresponds
// to (ppm/K; typical values).
inline constexpr double kExpansionSteelPpmPerK = 11.5;
inline constexpr double kExpansionAluminiumPpmPerK = 23.0;

struct IsotropicScale {
  bool found = false;
  std::vector<int> axes;  // the axes whose scales agree (0 = X …)
  // Per axis: its scale is the linear part of a smooth function (not a name).
  std::vector<bool> from_linear_part;
  double ppm = 0.0;    // their weighted mean
  double u_ppm = 0.0;  // its standard uncertainty
  double chi2 = 0.0;   // of the scales about the mean, axes.size() − 1 degrees of freedom
  // The temperature difference that gives it, K (ppm / α).
  double kelvin_steel() const { return ppm / kExpansionSteelPpmPerK; }
  double kelvin_aluminium() const { return ppm / kExpansionAluminiumPpmPerK; }
};

// From the named scales (significant, not ambiguous) of two or three axes,
// or for an axis without one, the scale in the linear part of a smooth
// function (SelectedTerm::linear_parts) whose value exceeds its uncertainty
// and whose function's linear share is at least kLinearPartMinShare:
// found when their χ² about the weighted mean is below the upper `alpha`
// quantile of χ² with (axes − 1) degrees of freedom.
IsotropicScale isotropic_scale(const std::vector<SelectedTerm>& effects, double alpha = 0.05);

}  // namespace abbe::diagnose
