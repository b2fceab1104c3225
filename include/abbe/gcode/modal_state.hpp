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

#include "abbe/gcode/modal_groups.hpp"
#include "abbe/gcode/motion.hpp"

namespace abbe::gcode {

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
  Eigen::Vector3d g92 = Eigen::Vector3d::Zero();
  Eigen::Vector3d g92_saved = Eigen::Vector3d::Zero();  // what G92.3 restores
  bool g43 = false;
  double tlo = 0.0;             // active tool length offset, program units (0 without G43)
  double tool_length_mm = 0.0;  // L of the G43 tool, mm

  double feed_mm = 0.0;  // mm/min
  double spindle = 0.0;
  int selected_tool = 0;
  int tool_in_spindle = 0;

  // Canned-cycle memory (program units): the sticky R, depth, P and Q words
  // and the initial level of a series of cycles (the G98 clearance).
  double cycle_r = 0.0, cycle_cc = 0.0, cycle_p = 0.0, cycle_q = 0.0;
  double cycle_initial_level = 0.0;
  bool cycle_initial_level_set = false;

  bool ended = false;  // M2 / M30 seen
};

}  // namespace abbe::gcode
