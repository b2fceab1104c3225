// LinuxCNC's predefined named parameters (RS274/NGC "Predefined Named
// Parameters", LinuxCNC 2.9) that abbe's state answers. Values as rs274ngc
// gives them, checked against the standalone rs274 (tests: program_runner_test):
// positions in program units; codes as G-code × 10 (G1 → 10, G81 → 810,
// G17 → 170, G54 → 540, G41.1 → 411); flags 1 or 0. Names rs274ngc knows
// but abbe does not follow (pockets, overrides, G96/G97, lathe modes,
// version numbers) are left undefined, so a program that reads them stops
// with "not defined" rather than run on a made-up value.
#include <cstring>

#include "abbe/gcode/interpreter.hpp"
#include "interpreter_steps.hpp"

namespace abbe::gcode {
namespace {

double flag(bool b) { return b ? 1.0 : 0.0; }

int plane_code(Plane p) { return p == Plane::xy ? 170 : p == Plane::xz ? 180 : 190; }

std::optional<double> axis_value(const detail::ExecState& st, char axis, bool absolute) {
  const Eigen::Vector3d p = absolute ? st.nose(st.pos) : st.pos;
  switch (axis) {
    case 'x':
      return p.x();
    case 'y':
      return p.y();
    case 'z':
      return p.z();
    case 'a':
    case 'b':
    case 'c':
      return st.rotary[static_cast<std::size_t>(axis - 'a')];
    case 'u':
    case 'v':
    case 'w':
      return 0.0;  // abbe has no U, V, W axes: they never move
    default:
      return std::nullopt;
  }
}

}  // namespace

std::optional<double> Interpreter::predefined_parameter(const std::string& name) const {
  const detail::ExecState& st = *state_;
  if (name.size() == 2 && name[0] == '_') return axis_value(st, name[1], false);
  if (name.size() == 6 && name.compare(0, 5, "_abs_") == 0) return axis_value(st, name[5], true);

  if (name == "_motion_mode") return st.motion_mode;
  if (name == "_plane") return plane_code(st.plane);
  if (name == "_ccomp") return st.comp.code;
  if (name == "_coord_system") return 540 + 10 * st.coord_index;
  if (name == "_metric") return flag(!st.inch);
  if (name == "_imperial") return flag(st.inch);
  if (name == "_absolute") return flag(!st.incremental);
  if (name == "_incremental") return flag(st.incremental);
  if (name == "_inverse_time") return flag(st.feed_mode == FeedMode::inverse_time);
  if (name == "_units_per_minute") return flag(st.feed_mode == FeedMode::units_per_minute);
  if (name == "_units_per_rev") return flag(st.feed_mode == FeedMode::units_per_rev);
  if (name == "_ijk_absolute_mode") return flag(st.arc_centre_absolute);
  if (name == "_tool_offset") return flag(st.g43);
  if (name == "_retract_r_plane") return flag(st.retract_to_r);
  if (name == "_retract_old_z") return flag(!st.retract_to_r);
  // The F word as written: rs274ngc keeps it across a G20/G21 switch.
  if (name == "_feed") return st.f_word;
  if (name == "_rpm") return st.spindle;
  if (name == "_spindle_on") return flag(st.spindle_direction != 0);
  if (name == "_spindle_cw") return flag(st.spindle_direction == 1);
  if (name == "_mist") return flag(st.mist);
  if (name == "_flood") return flag(st.flood);
  if (name == "_current_tool") return st.tool_in_spindle;
  if (name == "_selected_tool") return st.selected_tool;
  // 0: not run by LinuxCNC's task (a preview interpreter, as rs274 alone).
  if (name == "_task") return 0.0;
  return std::nullopt;
}

}  // namespace abbe::gcode
