#pragma once
// CampaignSetup: how the virtual laser campaign measures each axis — target
// spacing, runs, where the other axes stand and which tool is in the spindle
// (measured_at), the reflector point M_meas, and the reading noise.
#include <Eigen/Core>
#include <array>
#include <cstdint>

namespace abbe::sim {

struct AxisRecord {
  Eigen::Vector3d measured_at =
      Eigen::Vector3d::Zero();                      // tool tip P while the axis was measured, mm
  double tool_length = 0.0;                         // L while it was measured, mm
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // M_meas of the linear components, mm
  std::array<double, 6> sigma{};                    // reading noise per component (µm, µrad)
};

struct CampaignSetup {
  double spacing_mm = 25.0;  // target interval
  int runs = 5;              // runs per direction
  std::uint64_t seed = 1;    // noise stream
  double squareness_sigma_urad = 2.0;
  std::array<AxisRecord, 3> axes;
};

}  // namespace abbe::sim
