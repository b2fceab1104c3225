#pragma once
// HomePositions: the stored positions of G28 and G30 — machine coordinates
// of the spindle nose (s = P + L·e_z), mm, LinuxCNC's parameters 5161-5163
// and 5181-5183 — from the optional `home_positions` key of a machine file
// (docs/formats.md). Missing: the machine home (0, 0, 0).
#include <Eigen/Core>
#include <string>

namespace abbe::machine {

struct HomePositions {
  Eigen::Vector3d g28 = Eigen::Vector3d::Zero();
  Eigen::Vector3d g30 = Eigen::Vector3d::Zero();
};

// The `home_positions` of the machine file at `yaml_path` (validated when
// the machine was loaded); defaults when the file cannot be read (a machine
// built in memory). Throws abbe::InputError for a bad entry.
HomePositions read_home_positions(const std::string& yaml_path);

}  // namespace abbe::machine
