#pragma once
// Controller tables (`abbe export`, docs/export.md): the predicted errors of
// a machine handed to its control instead of being put into each program.
//  - Per-joint tables (LinuxCNC `COMP_FILE`): the positioning error of one
//    axis along its own direction, at a tool point the user names, as the
//    axis moves over its travel, forward and reverse.
//  - A volumetric grid: the deviation dx, dy, dz on a regular grid over the
//    travel, per model, for a volumetric compensation component.
// Both are evaluated with pipeline::ModelSet, the models predict and
// compensate use (with the same --extend overlay when one is given), and
// both come with the interpolation a control applies (linear along the
// joint, trilinear in the grid), so that a caller can check what the table
// leaves uncorrected.
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "abbe/machine/machine.hpp"
#include "abbe/model/error_extension.hpp"
#include "abbe/model/model_kind.hpp"

namespace abbe::compensate {

// LinuxCNC keeps at most 256 entries per joint (EMCMOT_COMP_SIZE).
inline constexpr std::size_t kLinuxCncMaxEntries = 256;
// The largest grid `export_grid` writes (nodes), so that a mistyped step
// gives an input error instead of a file of many gigabytes.
inline constexpr std::size_t kMaxGridNodes = 2'000'000;

// Positions lo, lo + h, …, hi with the spacing h = (hi − lo)/(n − 1) ≤ step
// (n = ceil((hi − lo)/step) + 1), or `count` positions when count ≥ 2.
// The ends are exact. Throws abbe::InputError (file "<command line>",
// field `option`) for a step ≤ 0 or not finite, a count < 2, or more than
// `max_points` positions.
std::vector<double> regular_positions(double lo, double hi, double step, std::size_t count,
                                      std::size_t max_points, const std::string& option);

// The per-joint table of one axis.
struct JointTable {
  machine::Axis axis = machine::Axis::x;
  std::vector<double> nominal_mm;  // axis position s_j (the joint's commanded position)
  std::vector<double> forward_um;  // predicted error along the axis, moving +, µm (P' − P)
  std::vector<double> reverse_um;  // the same moving −
  // The correction a control adds to the command at s (µm, = −error), linear
  // between the entries and constant beyond the ends, as LinuxCNC does.
  double correction_um(double s, int direction) const;
  bool direction_dependent() const;  // forward ≠ reverse somewhere
};

struct JointTableOptions {
  model::ModelKind model = model::ModelKind::ae_arm;
  std::shared_ptr<const model::ErrorExtension> extension;  // null: none
  Eigen::Vector3d at_tip = Eigen::Vector3d::Zero();  // tool tip P where the other axes stand, mm
  double tool_length = 0.0;                          // mm
  double step = 0.0;  // largest spacing, mm; 0: 5 mm, widened to fit kLinuxCncMaxEntries
  bool inch = false;  // the files in inch (LinuxCNC's LINEAR_UNITS = inch), else mm
};

// The tool tip at the centre of the travel (axis positions) for tool length
// L: the default tool point of the per-joint tables.
Eigen::Vector3d travel_centre_tip(const machine::Machine& machine, double tool_length);

// The tables of X, Y and Z over each axis' travel, the other two axes at
// the position of `at_tip` (axis positions s = P + L·e_z); the other axes'
// direction of motion is unknown and taken as the mean of forward and
// reverse. Throws abbe::InputError for a step giving more than 256 entries.
std::array<JointTable, 3> joint_tables(const machine::Machine& machine,
                                       const JointTableOptions& options);

// The COMP_FILE text for COMP_FILE_TYPE 1: one line per entry,
// "nominal forward_trim reverse_trim" in mm (in inch when `inch`), trims = −error (LinuxCNC adds
// the trim to the commanded joint position), no comment or header line
// (LinuxCNC stops reading at the first line that is not three numbers).
std::string linuxcnc_comp_text(const JointTable& table, bool inch = false);

// The INI lines that load the three files (joints 0, 1, 2 = X, Y, Z, as
// with trivkins), with a comment block naming the machine, model and tool
// point.
std::string linuxcnc_ini_text(const machine::Machine& machine, const JointTableOptions& options,
                              const std::array<JointTable, 3>& tables);

// A regular grid over the travel and the predicted deviation at its nodes.
struct VolumetricGrid {
  std::array<std::vector<double>, 3> nodes;  // tool tip positions per axis, mm (z = s_z − L)
  double tool_length = 0.0;                  // mm
  std::vector<model::ModelKind> models;
  // deviation[m][(k·ny + j)·nx + i]: model m at (x_i, y_j, z_k), µm, mean of
  // the directions (a grid has no direction of motion).
  std::vector<std::vector<Eigen::Vector3d>> deviation_um;

  std::size_t size() const { return nodes[0].size() * nodes[1].size() * nodes[2].size(); }
  // Trilinear interpolation of model m's deviation at tool tip p (clamped
  // to the grid), µm.
  Eigen::Vector3d interpolate(std::size_t m, const Eigen::Vector3d& p) const;
};

struct GridOptions {
  std::vector<model::ModelKind> models{model::ModelKind::ae_arm};
  std::shared_ptr<const model::ErrorExtension> extension;  // null: none
  double tool_length = 0.0;                                // mm
  // Per axis: the largest spacing (mm), or the number of nodes when count ≥ 2.
  Eigen::Vector3d step = Eigen::Vector3d::Constant(25.0);
  std::array<std::size_t, 3> count{0, 0, 0};
};

// Throws abbe::InputError for a bad step or count or more than kMaxGridNodes nodes.
VolumetricGrid volumetric_grid(const machine::Machine& machine, const GridOptions& options);

// The CSV: header `x,y,z,dx,dy,dz` (one model) or `x,y,z,dx_M,dy_M,dz_M,…`
// (M = the models' column suffixes), one row per node, x fastest, then y,
// then z; x, y, z the nominal tool tip (mm), d the predicted deviation
// P' − P (µm; the correction is its negative).
std::string grid_csv_text(const VolumetricGrid& grid);

// The whole of `abbe export linuxcnc`: writes x.comp, y.comp, z.comp and
// linuxcnc.ini into `dir` (created if missing; every file atomically) and
// returns a summary for the terminal (the INI lines and per-axis ranges).
std::string export_linuxcnc(const machine::Machine& machine, const JointTableOptions& options,
                            const std::string& dir);

// The whole of `abbe export grid`: writes the CSV to `path` ("-": stdout)
// atomically and returns a one-paragraph summary.
std::string export_grid(const machine::Machine& machine, const GridOptions& options,
                        const std::string& path);

}  // namespace abbe::compensate
