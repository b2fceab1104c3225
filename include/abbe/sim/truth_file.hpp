#pragma once
// The truth file (YAML): everything needed to rebuild a TruthMachine and its
// CampaignSetup exactly (all numbers written with 17 significant digits).
#include <string>

#include "abbe/sim/truth_generator.hpp"

namespace abbe::sim {

std::string truth_to_yaml(const GeneratedMachine& machine);
// Throws abbe::InputError naming `file`, the line and the field.
GeneratedMachine truth_from_yaml(const std::string& text, const std::string& file);
GeneratedMachine load_truth_file(const std::string& path);

}  // namespace abbe::sim
