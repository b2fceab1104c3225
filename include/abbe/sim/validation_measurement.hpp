#pragma once
// Validation measurement of the virtual machine: the truth (with its
// injected effects) sampled on a volumetric grid or along the fragmented
// path of an NC program, with noise, time stamps and direction signs;
// written as measured-data CSV (docs/formats.md).
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "abbe/io/measured_data.hpp"
#include "abbe/sim/truth_machine.hpp"

namespace abbe::sim {

struct MeasuredPoint {
  TipState tip;
  Eigen::Vector3d deviation_um = Eigen::Vector3d::Zero();
};

struct GridOptions {
  Eigen::Vector3d lo = Eigen::Vector3d::Zero();  // box of tool-tip positions P, mm
  Eigen::Vector3d hi = Eigen::Vector3d::Zero();
  double spacing_mm = 50.0;
  double tool_length = 0.0;
  double interval_s = 5.0;  // time per measured point (4 s dwell + move)
  int repeat = 1;           // the grid measured `repeat` times, sets "<set>1".."<set>N"
  bool one_setup = false;   // every pass in the one set `set` (one setup: one datum)
  std::string set = "grid";
};

// The default box: the whole travel, as tool-tip positions for `tool_length`.
void default_box(const TruthMachine& truth, double tool_length, Eigen::Vector3d& lo,
                 Eigen::Vector3d& hi);

// Points of the serpentine grid walk with directions and times (no deviations yet).
std::vector<TipState> grid_points(const GridOptions& options);

// Evaluates the truth (with effects) and adds Gaussian noise of `noise_um` per coordinate.
std::vector<MeasuredPoint> measure(const TruthMachine& truth, const std::vector<TipState>& tips,
                                   double noise_um, std::uint64_t seed);

std::string measured_to_csv(const std::vector<MeasuredPoint>& points);

// The same points as measured data in memory (what io::load_measured_data
// gives for that CSV, rows numbered from line 2), named `file`.
io::MeasuredData to_measured_data(const std::vector<MeasuredPoint>& points,
                                  const std::string& file);

}  // namespace abbe::sim
