#pragma once
// WorkspaceMap: the volumetric error of a machine over a grid of tool-tip
// positions (the whole travel or a box), per error model, with the
// statistics of the AE-arm paper's comparison (mean |d| of htm against
// ae-arm, and the difference in percent of htm).
#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "abbe/machine/machine.hpp"
#include "abbe/model/model_kind.hpp"

namespace abbe::identify {

struct MapOptions {
  Eigen::Vector3d lo = Eigen::Vector3d::Zero();  // box of tool tips P, mm
  Eigen::Vector3d hi = Eigen::Vector3d::Zero();
  double spacing_mm = 50.0;  // grid step; the box ends are always included
  double tool_length = 0.0;  // mm
  std::vector<model::ModelKind> models{model::ModelKind::htm, model::ModelKind::ae_arm,
                                       model::ModelKind::dual};
  // Optional: called now and then with the evaluations done so far (of
  // points × models), e.g. for a progress bar.
  std::function<void(std::size_t evaluations)> progress;
};

// The box of tool-tip positions the whole travel allows for a tool length:
// s = P + L·e_z, so P_z ranges over the z travel minus L.
void travel_box(const machine::Machine& machine, double tool_length, Eigen::Vector3d& lo,
                Eigen::Vector3d& hi);

// The grid positions along one axis: lo, lo + h, …, hi with h ≤ spacing.
std::vector<double> grid_axis(double lo, double hi, double spacing_mm);

struct ModelMapStats {
  model::ModelKind model = model::ModelKind::htm;
  double mean_um = 0.0;  // mean |d| over the grid
  double rms_um = 0.0;   // sqrt(mean |d|²)
  double max_um = 0.0;   // max |d|
  Eigen::Vector3d max_abs_component_um = Eigen::Vector3d::Zero();
  double second_order_max_um = 0.0;  // dual: max |ε² part|
  double second_order_rms_um = 0.0;
};

struct WorkspaceMap {
  std::vector<double> xs, ys, zs;       // grid axes
  std::vector<Eigen::Vector3d> points;  // x fastest, then y, then z
  std::vector<model::ModelKind> models;
  std::vector<std::vector<Eigen::Vector3d>> deviation_um;  // [model][point]
  std::vector<ModelMapStats> stats;                        // per model
  std::size_t out_of_range_lookups = 0;
  // htm vs ae-arm (when both are mapped).
  bool has_comparison = false;
  double mean_difference_um = 0.0;             // mean |d_htm| − mean |d_ae-arm|
  double percent_smaller = 0.0;                // of ae-arm's mean |d| relative to htm's, %
  double mean_abs_vector_difference_um = 0.0;  // mean |d_htm − d_ae-arm|
};

WorkspaceMap compute_map(const machine::Machine& machine, const MapOptions& options);

// CSV: x,y,z then per model <m>_dx,<m>_dy,<m>_dz,<m>_d (µm).
std::string map_to_csv(const WorkspaceMap& map);
// One plane of the grid: plane "xy" at the grid index `index` of the third
// axis (z), "xz" at y index, "yz" at x index. Columns: the two in-plane
// coordinates, the fixed one, then per model dx,dy,dz,d.
std::string map_slice_csv(const WorkspaceMap& map, const std::string& plane, std::size_t index);

}  // namespace abbe::identify
