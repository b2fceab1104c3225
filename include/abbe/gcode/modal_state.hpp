#pragma once
// ModalState: everything the interpreter remembers between blocks, as
// rs274ngc's setup structure does — the modal groups (units, distance modes,
// plane, motion mode, canned-cycle retract mode), the frame (position in the
// program frame, work offset, G92, tool length offset), feed, spindle and
// tool, and the canned-cycle memory. Positions and offsets are held in the
// program's current units and converted when G20/G21 switch, so that every
// decision (tolerances, peck loops) is taken on the same numbers as rs274ngc.
// Post-processors (the compensator) read it instead of re-deriving modes
// from the words of a block.
#include <Eigen/Core>
#include <array>

#include "abbe/gcode/modal_groups.hpp"
#include "abbe/gcode/motion.hpp"

namespace abbe::gcode {

// G93 / G94 / G95: what the F word means.
enum class FeedMode : std::uint8_t {
  inverse_time,      // G93: F is 1/minutes for the move (each feed move has its own F)
  units_per_minute,  // G94 (start-up)
  units_per_rev,     // G95: F is program units per spindle revolution
};

// G61 / G61.1 / G64: carried (the tool-tip path does not depend on them).
enum class PathControl : std::uint8_t { exact_path, exact_stop, blending };

struct ModalState {
  bool inch = false;                 // G20 (false: G21)
  bool incremental = false;          // G91 (false: G90)
  bool arc_centre_absolute = false;  // G90.1 (false: G91.1)
  Plane plane = Plane::xy;           // G17/G18/G19
  int motion_mode = gcode_id(80);    // gcode_id of the modal motion (G0..G3, cycles, G80)
  bool retract_to_r = true;          // G99 (false: G98); rs274ngc starts in G99

  // Program-frame position of the controlled point, program units: the
  // spindle nose s = (pos + g5x + g92 + tlo·e_z) in machine coordinates.
  Eigen::Vector3d pos = Eigen::Vector3d::Zero();
  int coord_index = 0;  // G54 = 0 … G59 = 5
  // Work offsets of G54 … G59, mm (from the configuration; G10 L2/L20 set them).
  std::array<Eigen::Vector3d, 6> work_offsets{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                                              Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                                              Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  // Stored positions of G28 / G30 (machine coordinates of the spindle nose,
  // mm; from the configuration, G28.1 / G30.1 store the current one).
  Eigen::Vector3d g28_home = Eigen::Vector3d::Zero();
  Eigen::Vector3d g30_home = Eigen::Vector3d::Zero();
  Eigen::Vector3d g92 = Eigen::Vector3d::Zero();
  Eigen::Vector3d g92_saved = Eigen::Vector3d::Zero();  // what G92.3 restores
  bool g43 = false;
  double tlo = 0.0;             // active tool length offset, program units (0 without G43)
  double tool_length_mm = 0.0;  // L of the G43 tool, mm
  // G43 with a tool that has no length in the table, where the configuration
  // allows it (`path`, `interpret`: the tip path does not depend on L while
  // G43 is active); the length is then taken as 0 and reported unknown.
  bool tool_length_unknown = false;
  bool unknown_tool_warned = false;

  FeedMode feed_mode = FeedMode::units_per_minute;
  // The F word in mm: mm/min (G94), mm/rev (G95) or 1/min (G93, not scaled).
  double feed_mm = 0.0;
  PathControl path_control = PathControl::blending;  // rs274ngc starts in G64
  double blend_tolerance = 0.0;                      // G64 P (program units; 0: none)
  double naive_cam_tolerance = 0.0;                  // G64 Q
  double spindle = 0.0;
  int spindle_direction = 0;  // M3: 1, M4: -1, M5: 0
  int selected_tool = 0;
  int tool_in_spindle = 0;

  // Canned-cycle memory (program units): the sticky R, depth, P and Q words
  // and the initial level of a series of cycles (the G98 clearance).
  double cycle_r = 0.0, cycle_cc = 0.0, cycle_p = 0.0, cycle_q = 0.0;
  double cycle_initial_level = 0.0;
  bool cycle_initial_level_set = false;

  bool ended = false;  // M2 / M30 seen, or the second '%' of a tape
  // '%' tape handling (LinuxCNC dialect): a program whose first non-blank
  // line is '%' ends at the next '%'.
  bool text_seen = false;
  bool percent_opened = false;
  // Rotary axes A, B, C (program units: degrees). abbe is a 3-axis model:
  // a rotary word is accepted while its axis stays where it is.
  std::array<double, 3> rotary{0.0, 0.0, 0.0};
  bool rotary_warned = false;  // the one warning for rotary words that never move
};

}  // namespace abbe::gcode
