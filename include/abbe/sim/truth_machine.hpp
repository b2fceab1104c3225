#pragma once
// TruthMachine: the ground truth of the virtual machine. Each axis j has an
// error motion E_j, a rigid motion of the tool relative to the workpiece:
//   E_j(p) = R_j·(p − C_j) + C_j + t_j,   R_j = exp([θ_j]) (exact rotation)
// with t_j and θ_j the linear (µm) and angular (µrad) components at s_j and
// C_j a pivot fixed in carriage j (C_j = pivot0 + Σ_{i∈U(j)} s_i·e_i). The
// tip under all errors is P' = E_a1(E_a2(E_a3(P))) for the axes a1 a2 a3 in
// chain order from `w` (the axis next to the tool acts first), plus the
// squareness term and the injected effects.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "abbe/sim/chain_layout.hpp"
#include "abbe/sim/effect.hpp"
#include "abbe/sim/error_component.hpp"

namespace abbe::sim {

struct AxisTruth {
  double travel_min = 0.0;  // mm, axis position s
  double travel_max = 0.0;
  Eigen::Vector3d pivot0 = Eigen::Vector3d::Zero();  // C_j with all axes at 0, mm
  std::array<ErrorComponent, 6> components;          // EXj EYj EZj (µm) EAj EBj ECj (µrad)
};

struct Squareness {
  double ec0y = 0.0, eb0z = 0.0, ea0z = 0.0;  // µrad
};

// Where and how the tool tip is when the truth is asked.
struct TipState {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();  // tool tip P, machine coordinates, mm
  double tool_length = 0.0;                     // L, mm (s = P + L·e_z)
  std::array<int, 3> dir{0, 0, 0};              // sign of the last motion per axis
  double time = 0.0;                            // s since the campaign start
  std::string set;                              // `set` label
};

class TruthMachine {
 public:
  std::string name = "virtual machine";
  ChainLayout chain;
  double tool_length = 0.0;          // mm, tool in the spindle without G43
  std::map<int, double> tool_table;  // H -> mm
  Squareness squareness;
  std::array<AxisTruth, 3> axes;
  std::vector<Effect> effects;  // not in the laser tables

  // Linear (µm) and angular (µrad) error motion of axis j at position s_j.
  Eigen::Vector3d translation_um(int j, double s_j, int dir) const;
  Eigen::Vector3d rotation_urad(int j, double s_j, int dir) const;
  Eigen::Vector3d pivot(int j, const Eigen::Vector3d& s) const;
  // E_j(p) − p in mm at axis positions s.
  Eigen::Vector3d axis_displacement_mm(int j, const Eigen::Vector3d& s, int dir,
                                       const Eigen::Vector3d& p) const;
  // What a laser reads for the linear components of axis j at the point M
  // when only axis j moves: E_j(M) − M in µm.
  Eigen::Vector3d laser_linear_reading_um(int j, const Eigen::Vector3d& s, int dir,
                                          const Eigen::Vector3d& m) const;

  // P' − P in µm: exact composition + squareness (no effects).
  Eigen::Vector3d geometric_deviation_um(const TipState& tip) const;
  // The same plus every injected effect.
  Eigen::Vector3d deviation_um(const TipState& tip) const;
  // The effects alone, µm.
  Eigen::Vector3d effects_um(const TipState& tip) const;

  static Eigen::Vector3d axis_positions(const Eigen::Vector3d& p, double tool_length) {
    return p + Eigen::Vector3d(0.0, 0.0, tool_length);
  }
};

// (R − I)·v for R = exp([θ]) (θ in rad), accurate for tiny |θ|.
Eigen::Vector3d rotation_minus_identity_times(const Eigen::Vector3d& theta,
                                              const Eigen::Vector3d& v);

}  // namespace abbe::sim
