#pragma once
// The `home_positions` key of a machine file, read with the machine file's
// YAML reader (private to the library: Machine::parse validates it,
// read_home_positions returns it).
#include <yaml-cpp/yaml.h>

#include "abbe/machine/home_positions.hpp"
#include "src/io/yaml_reader.hpp"

namespace abbe::machine::detail {

HomePositions parse_home_positions(const io::YamlReader& r, const YAML::Node& root);

}  // namespace abbe::machine::detail
