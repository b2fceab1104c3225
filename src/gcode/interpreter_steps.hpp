#pragma once
// The interpreter's steps, in rs274ngc's manner (private to the library):
// read (classify_block: every word into its modal group) → check (which
// motion the block makes; every word has a code that uses it, word_use.hpp)
// → convert_* in the documented order of execution (interpreter.hpp).
#include <Eigen/Core>
#include <functional>
#include <string>

#include "abbe/gcode/interpreter.hpp"
#include "abbe/gcode/modal_groups.hpp"
#include "abbe/gcode/modal_state.hpp"
#include "abbe/io/units.hpp"

namespace abbe::gcode::detail {

// The modal state with the configuration it is read against.
struct ExecState : ModalState {
  InterpreterConfig config;
  std::string file;
  Block adapted;  // the block in RS274/NGC when the program is in another dialect
  const Block* read_block = nullptr;  // what the last execute() read
  int read_non_modal = -1;            // its group-0 code (gcode_id), -1: none
  // Fanuc/Haas: canned cycles are a modal group of their own (09), so the
  // last G0-G3 is still in force after G80 (LinuxCNC: no motion mode).
  int fanuc_group01 = gcode_id(80);

  double unit() const { return inch ? units::kMmPerInch : 1.0; }
  Eigen::Vector3d g5x() const {
    return work_offsets[static_cast<std::size_t>(coord_index)] / unit();
  }
  double active_length_mm() const { return g43 ? tool_length_mm : config.default_tool_length; }
  // The spindle nose of a program-frame point, program units (machine frame).
  Eigen::Vector3d nose(const Eigen::Vector3d& p) const {
    return p + g5x() + g92 + Eigen::Vector3d(0, 0, tlo);
  }
  // The feed rate of a feed move of `length_mm` (mm/min) in the feed mode.
  double feed_rate_mm(double length_mm) const;
  // Tool tip P (machine, mm) of a program-frame point. In mm the unit
  // factors are 1 and are left out (the same doubles, no divisions).
  Eigen::Vector3d tip(const Eigen::Vector3d& p) const;
};

// What the check step found in one block.
struct BlockPlan {
  const BlockCodes& codes;
  const BlockContext& ctx;
  int non_modal = -1;                 // gcode_id of group 0, -1: none
  int motion = -1;                    // gcode_id of the motion the block makes, -1: none
  const Word* motion_word = nullptr;  // where the motion is written (or its first axis word)
};

// Hands one motion of the block on (numbers it, adds tool and spindle).
using Emit = std::function<void(Motion&)>;

bool is_cycle(int code);
// Non-modal codes that take the block's axis words (G10 G28 G30 G52 G92).
bool uses_axis_words(int non_modal);
bool is_integer(double v);
const char* plane_name(Plane plane);

// check: the motion of the block and the word-use rules.
BlockPlan plan_block(const ModalState& st, const BlockCodes& codes, const BlockContext& ctx);
// check: rotary words A, B, C that do not move (warned once), or an error.
void check_rotary_words(ExecState& st, const BlockPlan& b);

// convert_*: one per step of the order of execution.
void convert_feed_mode(ExecState& st, const BlockPlan& b);                // G93/G94/G95
void convert_feed_speed_tool(ExecState& st, const BlockPlan& b);          // F, S, T, M6
void convert_dwell(ExecState& st, const BlockPlan& b, const Emit& emit);  // G4
void convert_plane(ExecState& st, const BlockPlan& b);                    // G17-G19
void convert_units(ExecState& st, const BlockPlan& b);                    // G20/G21
void convert_tool_length(ExecState& st, const BlockPlan& b);              // G43/G49
void convert_coord_system(ExecState& st, const BlockPlan& b);             // G54-G59
void convert_path_control(ExecState& st, const BlockPlan& b);             // G61/G61.1/G64
void convert_distance_modes(ExecState& st, const BlockPlan& b);  // G90/G91, G90.1/G91.1, G98/G99
void convert_setup(ExecState& st, const BlockPlan& b);           // G10 L1/L2/L10/L20
void convert_home(ExecState& st, const BlockPlan& b, const Emit& emit);    // G28/G30, .1
void convert_axis_offsets(ExecState& st, const BlockPlan& b);              // G92 family, G52
void convert_motion(ExecState& st, const BlockPlan& b, const Emit& emit);  // G0-G3, cycles, G80
void convert_stop(ExecState& st, const BlockPlan& b);                      // M2/M30

// The motion kinds of convert_motion (end: the end point in the program frame).
void convert_straight(ExecState& st, const BlockPlan& b, const Eigen::Vector3d& end,
                      const Emit& emit);
void convert_arc(ExecState& st, const BlockPlan& b, const Eigen::Vector3d& end, const Emit& emit);
void convert_cycle(ExecState& st, const BlockPlan& b, const Emit& emit);

}  // namespace abbe::gcode::detail
