#pragma once
// The interpreter's steps, in rs274ngc's manner (private to the library):
// read (classify_block: every word into its modal group) → check (which
// motion the block makes; every word has a code that uses it, word_use.hpp)
// → convert_* in the documented order of execution (interpreter.hpp).
#include <Eigen/Core>
#include <cmath>
#include <string>
#include <vector>

#include "abbe/gcode/interpreter.hpp"
#include "abbe/gcode/modal_groups.hpp"
#include "abbe/gcode/modal_state.hpp"
#include "abbe/io/units.hpp"
#include "hot.hpp"

namespace abbe::gcode::detail {

// What M70/M73 save and M72 restores (rs274ngc's saved context: units,
// plane, distance modes, feed mode and rate, coordinate system, tool length
// offset on/off, retract mode, path control, spindle speed and direction).
struct SavedModes {
  bool inch = false;
  bool incremental = false;
  bool arc_centre_absolute = false;
  Plane plane = Plane::xy;
  FeedMode feed_mode = FeedMode::units_per_minute;
  double feed_mm = 0.0;
  int coord_index = 0;
  bool g43 = false;
  bool retract_to_r = true;
  PathControl path_control = PathControl::blending;
  double blend_tolerance = 0.0;
  double naive_cam_tolerance = 0.0;
  double spindle = 0.0;
  int spindle_direction = 0;
};
// One call level's saved state.
struct SaveSlot {
  bool valid = false;
  bool autorestore = false;  // M73: restored by the level's return
  SavedModes modes;
};

// Cutter radius compensation (G41/G42/G41.1/G42.1, G40), rs274ngc's way:
// the tool centre is offset by the radius to the left or right of the
// programmed XY path; every compensated motion waits in a queue until the
// next one is known (an inside corner moves its end point back to the
// intersection, an outside corner inserts an arc about the programmed corner).
struct CompEntry {
  Motion m;  // kind, line, sub, feed, tool data, rotation (coordinates set when flushed)
  Eigen::Vector3d end = Eigen::Vector3d::Zero();     // program frame, program units
  Eigen::Vector2d dir = Eigen::Vector2d::Zero();     // straights: programmed XY direction
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  // arcs: XY centre, program frame
  double original_turns = 0.0;  // arcs: sweep (radians) as queued; 0: not checked
};
struct CutterComp {
  int code = gcode_id(40);  // G40, G41, G41.1, G42, G42.1 (as gcode_id) in force
  int side = 0;             // 1: left (G41), -1: right (G42), 0: off
  double radius = 0.0;      // program units; 0: no offset although the side is set
  bool first_move = true;
  Eigen::Vector3d current = Eigen::Vector3d::Zero();  // tool centre, program frame
  std::vector<CompEntry> queue;
  Eigen::Vector3d queue_start = Eigen::Vector3d::Zero();  // where queue[0] starts
  Eigen::Vector2d endpoint = Eigen::Vector2d::Zero();     // XY start of queue[0]
  bool endpoint_valid = false;
  // After G40: the tool stands at the last compensated point, the program
  // continues from the programmed one; the next motion starts there. A tool
  // change (M6) makes rs274ngc take the tool's position as the current one.
  bool fanuc_warned = false;  // the one warning about Fanuc's own rules
  bool exit_pending = false;
  Eigen::Vector3d exit_nose_mm = Eigen::Vector3d::Zero();  // spindle nose, machine, mm
  bool offsetting() const { return side != 0 && radius > 0.0; }
};

// A callable on a Motion held as a function pointer and its context.
struct MotionHook {
  void (*fn)(void*, Motion&) = nullptr;
  void* ctx = nullptr;
  void operator()(Motion& m) const { fn(ctx, m); }
};
template <class F>
MotionHook make_hook(F& f) {
  return {[](void* c, Motion& m) { (*static_cast<F*>(c))(m); }, &f};
}

// The modal state with the configuration it is read against.
struct ExecState : ModalState {
  InterpreterConfig config;
  std::size_t delivered = 0;  // motions handed to a sink
  std::string file;
  Block adapted;  // the block in RS274/NGC when the program is in another dialect
  const Block* read_block = nullptr;  // what the last execute() read
  int read_non_modal = -1;            // its group-0 code (gcode_id), -1: none
  // Fanuc/Haas: canned cycles are a modal group of their own (09), so the
  // last G0-G3 is still in force after G80 (LinuxCNC: no motion mode).
  int fanuc_group01 = gcode_id(80);
  // M70-M73: one slot per subroutine call level (the main program is level 0).
  std::vector<SaveSlot> save_slots = std::vector<SaveSlot>(1);
  CutterComp comp;
  double f_word = 0.0;  // the F word as written (program units, or 1/min in G93): #<_feed>
  bool mist = false;    // M7 (M9 ends it); carried, not motion
  bool flood = false;   // M8 (M9 ends it)
  // Hands a finished motion to the caller's sink, and numbers a motion of
  // the current block (set by each execute call; plain function pointers,
  // so that the per-block cost stays that of the plain-block path).
  MotionHook deliver;
  MotionHook stamp;

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
  double feed_rate_mm(double length_mm) const {
    switch (feed_mode) {
      case FeedMode::inverse_time:
        return length_mm * feed_mm;  // the move takes 1/F minutes
      case FeedMode::units_per_rev:
        return feed_mm * std::abs(spindle);
      case FeedMode::units_per_minute:
        break;
    }
    return feed_mm;
  }
  // Tool tip P (machine, mm) of a program-frame point. In mm the unit
  // factors are 1 and are left out (the same doubles, no divisions).
  // Inline: it runs for both ends of every motion.
  Eigen::Vector3d tip(const Eigen::Vector3d& p) const {
    Eigen::Vector3d s;
    if (inch) {
      s = (p + g5x() + g92 + Eigen::Vector3d(0, 0, tlo)) * units::kMmPerInch;
    } else {
      s = p + work_offsets[static_cast<std::size_t>(coord_index)] + g92 +
          Eigen::Vector3d(0, 0, tlo);
    }
    s.z() -= active_length_mm();
    return s;
  }
  // The spindle nose (machine, mm) of a program-frame point, and back.
  Eigen::Vector3d nose_mm(const Eigen::Vector3d& p) const {
    return tip(p) + Eigen::Vector3d(0, 0, active_length_mm());
  }
  Eigen::Vector3d program_of_nose(const Eigen::Vector3d& nose) const {
    return nose / unit() - g5x() - g92 - Eigen::Vector3d(0, 0, tlo);
  }
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
using Emit = MotionHook;

// G73 G74 G81-G87 G89 (inline: asked for every motion).
inline bool is_cycle(int code) {
  if (code < gcode_id(73) || code > gcode_id(89)) return false;
  return code == gcode_id(73) || code == gcode_id(74) ||
         (code >= gcode_id(81) && code <= gcode_id(87) && code % 10 == 0) || code == gcode_id(89);
}
// Non-modal codes that take the block's axis words (G10 G28 G30 G52 G92).
bool uses_axis_words(int non_modal);
bool is_integer(double v);
const char* plane_name(Plane plane);

// check: the motion of the block and the word-use rules.
BlockPlan plan_block(const ModalState& st, const BlockCodes& codes, const BlockContext& ctx);
// A plain block (most of a CAM program): no G code but a motion code, no M
// code, cutter compensation off, and either a straight move (G0/G1, or
// none) with only X Y Z F S T words, or an arc (G2/G3) with only X Y Z I J
// K R P F S T words. Nothing that plan_block, check_rotary_words or
// check_comp_block refuse can occur in it (the arc's I J K R P are the
// words G2/G3 use), so plan_plain_block only finds its motion (as
// plan_block does).
bool is_plain_block(const ExecState& st, const BlockCodes& codes);
BlockPlan plan_plain_block(const ModalState& st, const BlockCodes& codes, const BlockContext& ctx);
// check: rotary words A, B, C that do not move (warned once), or an error.
void check_rotary_words(ExecState& st, const BlockPlan& b);

// convert_*: one per step of the order of execution.
void convert_feed_mode(ExecState& st, const BlockPlan& b);                // G93/G94/G95
void convert_feed_speed_tool(ExecState& st, const BlockPlan& b);          // F, S, T, M6
void convert_modal_save(ExecState& st, const BlockPlan& b);               // M70-M73
void convert_dwell(ExecState& st, const BlockPlan& b, const Emit& emit);  // G4
void convert_plane(ExecState& st, const BlockPlan& b);                    // G17-G19
void convert_units(ExecState& st, const BlockPlan& b);                    // G20/G21
void convert_cutter_comp(ExecState& st, const BlockPlan& b);              // G40/G41/G42
void convert_tool_length(ExecState& st, const BlockPlan& b);              // G43/G49
void convert_coord_system(ExecState& st, const BlockPlan& b);             // G54-G59
void convert_path_control(ExecState& st, const BlockPlan& b);             // G61/G61.1/G64
void convert_distance_modes(ExecState& st,
                            const BlockPlan& b);        // G90/G91, G90.1/G91.1, G98/G99
void convert_setup(ExecState& st, const BlockPlan& b);  // G10 L1/L2/L10/L20
void convert_home(ExecState& st, const BlockPlan& b, const Emit& emit);  // G28/G30, .1
void convert_axis_offsets(ExecState& st, const BlockPlan& b);            // G92 family, G52
void convert_motion(ExecState& st, const BlockPlan& b,
                    const Emit& emit);                 // G0-G3, cycles, G80
void convert_stop(ExecState& st, const BlockPlan& b);  // M2/M30

// G20/G21: converts everything held in program units.
void set_units(ExecState& st, bool inch);
// M72 and M73's return: the saved modes back (G43 re-applied with the tool
// in the spindle, as rs274ngc does). `at`: the word errors point at.
void restore_modes(ExecState& st, const SavedModes& saved, const BlockContext& ctx, const Word* at);

// Cutter radius compensation (cutter_comp.cpp). check_comp_block refuses
// what cannot be done while it is on; comp_straight / comp_arc queue the
// compensated motions of a block (`m`: the stamped motion of the block,
// kind, feed, rotation); comp_flush hands the queue on unchanged (M0-M2,
// M30, the end of the program).
void check_comp_block(const ExecState& st, const BlockPlan& b);
void comp_straight(ExecState& st, const BlockPlan& b, const Eigen::Vector3d& end, const Motion& m);
void comp_arc(ExecState& st, const BlockPlan& b, const Eigen::Vector3d& end,
              const Eigen::Vector2d& centre, const Motion& m);
void comp_flush(ExecState& st);
void comp_enqueue_dwell(ExecState& st, const Motion& m);

// What every motion code leaves behind before it is converted: a motion
// other than a canned cycle ends the cycles' initial level; G0-G3 stay the
// Fanuc group-01 code that G80 returns to.
void note_motion_code(ExecState& st, int motion);
// The end point of the block's motion in the program frame (rs274ngc's
// find_ends: axis words, G90/G91, G53, polar words).
Eigen::Vector3d motion_end(ExecState& st, const BlockPlan& b);
// The G0/G1 motion from the current point to `end` (feed checked; sets the
// motion mode; the position is left to the caller).
Motion straight_motion(ExecState& st, const BlockPlan& b, const Eigen::Vector3d& end);
// Numbers motion `sub` of the block at `line` and adds the tool and spindle
// data in force.
void stamp_motion(const ExecState& st, Motion& m, std::size_t line, std::uint32_t sub);
// Hands a finished motion to the sink: a coordinate beyond the bound, or a
// sink's MotionRefused, is an InputError at the block's first axis, centre
// or radius word.
void deliver_motion(ExecState& st, Motion& m, const Block& block, const BlockContext& ctx,
                    const MotionSink& sink);
// The one motion of a plain block (is_plain_block), with no motion held
// back by cutter compensation: stamped and delivered.
ABBE_HOT void convert_plain_motion(ExecState& st, const BlockPlan& b, const Block& block,
                                   const MotionSink& sink);

// The motion kinds of convert_motion (end: the end point in the program frame).
void convert_straight(ExecState& st, const BlockPlan& b, const Eigen::Vector3d& end,
                      const Emit& emit);
ABBE_HOT void convert_arc(ExecState& st, const BlockPlan& b, const Eigen::Vector3d& end,
                          const Emit& emit);
void convert_cycle(ExecState& st, const BlockPlan& b, const Emit& emit);

}  // namespace abbe::gcode::detail
