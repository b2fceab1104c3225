#pragma once
// Machine: the immutable description of one 3-axis machine tool — kinematic
// chain, travels, tools, work offsets, squareness, the measurement record of
// each axis and its component table (the "Model" of a Model/Data pair; the
// error models in abbe/model/ are built from it). Loaded from the YAML
// machine file of docs/formats.md.
#include <Eigen/Core>
#include <array>
#include <map>
#include <optional>
#include <string>

#include "abbe/machine/axis.hpp"
#include "abbe/machine/campaign_uncertainty.hpp"
#include "abbe/machine/component_table.hpp"
#include "abbe/machine/kinematic_chain.hpp"
#include "abbe/machine/reference_conventions.hpp"

namespace abbe::machine {

enum class OutOfRangePolicy : std::uint8_t { clamp, extrapolate, error };
const char* to_string(OutOfRangePolicy p);

struct Travel {
  double min = 0.0, max = 0.0;  // mm
};

// Squareness, µrad (ISO 230-1 names; X reference, Y secondary).
struct Squareness {
  double ec0y = 0.0;  // Y to X, about Z
  double eb0z = 0.0;  // Z to X, about Y
  double ea0z = 0.0;  // Z to Y, about X
};

// How axis j was measured: the tool tip P and tool length L while the laser
// ran (the other axes stood still there), and the measurement point
// M_{j,k}^meas (reflector position, machine coordinates, mm) of each linear
// component k = X, Y, Z.
struct AxisRecord {
  bool present = false;  // false: the machine file has no record for this axis
  Eigen::Vector3d measured_tip = Eigen::Vector3d::Zero();  // P^meas, mm
  double measured_tool_length = 0.0;                       // L_meas, mm
  std::array<Eigen::Vector3d, 3> point{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                                       Eigen::Vector3d::Zero()};
  // Axis positions while measured: s^meas = P^meas + L_meas·e_z.
  Eigen::Vector3d measured_axes() const {
    return measured_tip + Eigen::Vector3d(0.0, 0.0, measured_tool_length);
  }
};

struct MachineSpec {
  std::string name;
  std::string file;  // the YAML file it was read from ("<memory>" when built in code)
  KinematicChain chain = KinematicChain::parse("w X' b Y Z t");
  std::array<Travel, 3> travel{};
  double tool_length = 0.0;                   // mm, the tool in the spindle without G43
  std::map<int, double> tool_table;           // H -> L, mm
  std::map<int, double> tool_diameters;       // T -> diameter, mm (G41/G42 radius = diameter/2)
  std::array<Eigen::Vector3d, 6> work_offsets{// G54..G59, mm
                                              Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                                              Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                                              Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  Squareness squareness;
  OutOfRangePolicy out_of_range = OutOfRangePolicy::clamp;
  std::array<AxisRecord, 3> axes;
  ComponentTable table;
  std::string table_file;            // resolved path of the component table
  CampaignUncertainty uncertainty;   // optional `uncertainty` key (not given: zero)
  ReferenceConventions conventions;  // optional `conventions` key (not given: absolute)
};

class Machine {
 public:
  // Validates the spec (records present where the table needs them).
  explicit Machine(MachineSpec spec);

  // Reads and validates a machine file; the component table path is taken
  // relative to the YAML file. Throws abbe::InputError (file, line, field).
  static Machine load(const std::string& yaml_path);
  // The same from YAML text; `file` names it in messages and relative table
  // paths resolve against `base_dir`.
  static Machine parse(const std::string& yaml_text, const std::string& file,
                       const std::string& base_dir);

  const MachineSpec& spec() const { return spec_; }
  const std::string& name() const { return spec_.name; }
  const KinematicChain& chain() const { return spec_.chain; }
  const Travel& travel(Axis a) const { return spec_.travel[static_cast<std::size_t>(index(a))]; }
  double tool_length() const { return spec_.tool_length; }
  const std::map<int, double>& tool_table() const { return spec_.tool_table; }
  const std::map<int, double>& tool_diameters() const { return spec_.tool_diameters; }
  const std::array<Eigen::Vector3d, 6>& work_offsets() const { return spec_.work_offsets; }
  const Squareness& squareness() const { return spec_.squareness; }
  OutOfRangePolicy out_of_range() const { return spec_.out_of_range; }
  const AxisRecord& record(Axis a) const { return spec_.axes[static_cast<std::size_t>(index(a))]; }
  const ComponentTable& table() const { return spec_.table; }
  const CampaignUncertainty& uncertainty() const { return spec_.uncertainty; }

  // The same machine with other values of its campaign (a Monte Carlo draw):
  // the table must have the same series as this one's, so the constructor's
  // checks still hold and are not repeated (nor logged again).
  Machine with_campaign(ComponentTable table, std::array<AxisRecord, 3> axes,
                        Squareness squareness) const;

 private:
  struct Unchecked {};
  Machine(MachineSpec spec, Unchecked) : spec_(std::move(spec)) {}
  MachineSpec spec_;
};

}  // namespace abbe::machine
