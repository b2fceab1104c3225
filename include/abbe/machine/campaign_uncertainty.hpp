#pragma once
// CampaignUncertainty: the standard uncertainties (GUM, k = 1) of the laser
// campaign behind a machine — the optional `uncertainty` key of the machine
// file and the optional `uncertainty` column of the component table
// (docs/formats.md) — and one Monte Carlo draw of that campaign: the machine
// with its table values, reflector points and squareness perturbed by them
// (docs/models.md, "Uncertainty of the prediction").
#include <array>
#include <functional>
#include <string>

#include "abbe/machine/axis.hpp"

namespace abbe::machine {

class Machine;  // machine.hpp

struct CampaignUncertainty {
  bool given = false;  // the machine file has an `uncertainty` key
  // The laser's own uncertainty of the positioning readings (EXX, EYY, EZZ):
  // constant_um + ppm·10⁻³·|s − s₀| µm (s₀ the series' first target), as the
  // manufacturer states it; the constant is drawn per target, the ppm part
  // once per component (a scale error of the whole series).
  double laser_constant_um = 0.0;
  double laser_ppm = 0.0;
  // Per component (index axis·6 + d): the standard uncertainty of every value
  // of the component (µm or µrad), drawn per target.
  std::array<double, 3 * kComponentsPerAxis> component{};
  // Every coordinate of every reflector (measurement) point, mm.
  double reflector_mm = 0.0;
  // Squareness EC0Y, EB0Z, EA0Z, µrad.
  std::array<double, 3> squareness_urad{0.0, 0.0, 0.0};
};

// True when the machine file or its table gives any uncertainty (the key, or
// the table's `uncertainty` column); false: nothing to propagate.
bool has_campaign_uncertainty(const Machine& machine);

// Throws abbe::InputError (the machine file, field `uncertainty`) unless
// has_campaign_uncertainty(machine): `option` (e.g. "--uncertainty") has
// nothing to propagate.
void require_campaign_uncertainty(const Machine& machine, const std::string& option);

// What is propagated, in words ("table values (per-target u, 480 values);
// laser 0.1 µm + 0.5 ppm; reflector points 1 mm"), for the summaries.
std::string campaign_uncertainty_text(const Machine& machine);

// One draw: the machine with every table value, reflector point and
// squareness value perturbed by normal deviates of the standard uncertainties
// above. `standard_normal` returns N(0, 1) deviates; it is called a fixed
// number of times per draw for a given machine (so a seeded stream gives the
// same draws whatever the uncertainties are).
Machine draw_campaign(const Machine& machine, const std::function<double()>& standard_normal);

}  // namespace abbe::machine
