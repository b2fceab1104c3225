#pragma once
// Generates a TruthMachine and a matching CampaignSetup from a seed and a
// profile ("mazak": shaped after the thesis' Mazak AJV 25-405, Tables 4–6;
// "generic": random magnitudes in realistic ranges). Distributions and
// magnitudes: docs/virtual-machine.md.
#include <cstdint>
#include <optional>
#include <string>

#include "abbe/sim/campaign_setup.hpp"
#include "abbe/sim/truth_machine.hpp"

namespace abbe::sim {

struct GeneratedMachine {
  TruthMachine truth;
  CampaignSetup campaign;
};

struct GeneratorOptions {
  std::uint64_t seed = 1;
  std::string profile = "mazak";  // "mazak" | "generic"
  std::string chain = "w X' b Y Z t";
  double spacing_mm = 25.0;
  int runs = 5;
  double noise_scale = 1.0;    // multiplies every reading noise (0: noise-free campaign)
  double angular_scale = 1.0;  // multiplies every angular component (e.g. 50 for ≈ 1 mrad)
  // Noise of the separate squareness measurement (µrad, one standard
  // deviation), used as given (not multiplied by noise_scale). Unset: the
  // profile's default — mazak 0 (the thesis' squareness is itself a
  // measurement result, carried over as is), generic 2 µrad × noise_scale.
  std::optional<double> squareness_sigma_urad;
};

// Throws std::invalid_argument for an unknown profile, a bad chain or a
// negative or non-finite squareness sigma.
GeneratedMachine generate_machine(const GeneratorOptions& options);

}  // namespace abbe::sim
