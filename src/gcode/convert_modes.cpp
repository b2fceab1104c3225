// The convert_* steps that change modes and the frame (no motion but G4).
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>

#include "interpreter_steps.hpp"

namespace abbe::gcode::detail {

void convert_feed_mode(ExecState& st, const BlockPlan& b) {
  const auto& g = b.codes.group(GGroup::feed_mode);
  if (!g) return;
  const FeedMode mode = g->code == gcode_id(93)   ? FeedMode::inverse_time
                        : g->code == gcode_id(95) ? FeedMode::units_per_rev
                                                  : FeedMode::units_per_minute;
  // rs274ngc: entering or leaving inverse time sets the feed rate to 0.
  if (mode != st.feed_mode &&
      (mode == FeedMode::inverse_time || st.feed_mode == FeedMode::inverse_time))
    st.feed_mm = 0.0;
  st.feed_mode = mode;
}

void convert_feed_speed_tool(ExecState& st, const BlockPlan& b) {
  const BlockCodes& c = b.codes;
  if (const Word* f = c.word('F')) {
    if (f->value < 0) b.ctx.fail(f, "negative feed rate (F)");
    st.feed_mm = st.feed_mode == FeedMode::inverse_time ? f->value : f->value * st.unit();
  }
  if (const Word* s = c.word('S')) {
    if (s->value < 0) b.ctx.fail(s, "negative spindle speed (S)");
    st.spindle = s->value;
  }
  if (const Word* t = c.word('T')) {
    if (t->value < 0 || !is_integer(t->value))
      b.ctx.fail(t, "T word must be a non-negative integer");
    st.selected_tool = static_cast<int>(std::lround(t->value));
  }
  if (c.group(MGroup::tool_change)) st.tool_in_spindle = st.selected_tool;
  if (const auto& m = c.group(MGroup::spindle))
    st.spindle_direction = m->code == 3 ? 1 : m->code == 4 ? -1 : 0;
}

void convert_dwell(ExecState& st, const BlockPlan& b, const Emit& emit) {
  if (b.non_modal != gcode_id(4)) return;
  const Word* p = b.codes.word('P');
  if (!p)
    b.ctx.fail(b.codes.group(GGroup::non_modal)->word, "dwell (G4) without a P word (seconds)");
  if (p->value < 0) b.ctx.fail(p, "negative dwell time (G4 P)");
  Motion m;
  m.kind = MotionKind::dwell;
  m.start = m.end = st.tip(st.pos);
  m.dwell_seconds = p->value;
  emit(m);
}

void convert_plane(ExecState& st, const BlockPlan& b) {
  if (const auto& g = b.codes.group(GGroup::plane)) {
    st.plane = g->code == gcode_id(17)   ? Plane::xy
               : g->code == gcode_id(18) ? Plane::xz
                                         : Plane::yz;
  }
}

// Everything held in program units is converted.
void convert_units(ExecState& st, const BlockPlan& b) {
  const auto& g = b.codes.group(GGroup::units);
  if (!g) return;
  const bool inch = g->code == gcode_id(20);
  if (inch == st.inch) return;
  const double k = inch ? 1.0 / units::kMmPerInch : units::kMmPerInch;
  st.pos *= k;
  st.g92 *= k;
  st.g92_saved *= k;
  st.tlo *= k;
  st.cycle_r *= k;
  st.cycle_cc *= k;
  st.cycle_q *= k;
  st.cycle_initial_level *= k;
  st.inch = inch;
}

// The spindle does not move, the program frame does.
void convert_tool_length(ExecState& st, const BlockPlan& b) {
  const BlockCodes& c = b.codes;
  const auto& tool_length = c.group(GGroup::tool_length);
  if (!tool_length) return;
  double new_tlo = 0.0;
  if (tool_length->code == gcode_id(43)) {
    int h = st.tool_in_spindle;
    if (const Word* hw = c.word('H')) {
      if (hw->value < 0 || !is_integer(hw->value))
        b.ctx.fail(hw, "H word must be a non-negative integer");
      if (hw->value > 99999.0) b.ctx.fail(hw, "H word (tool number) is above 99999");
      h = static_cast<int>(std::lround(hw->value));
    }
    double length = 0.0;
    st.tool_length_unknown = false;
    if (h != 0) {
      const auto it = st.config.tool_lengths.find(h);
      if (it != st.config.tool_lengths.end()) {
        length = it->second;
      } else if (st.config.allow_unknown_tool_length) {
        // The tip path does not depend on L while G43 is active (s - L with
        // s = P + L): taken as 0, reported unknown.
        st.tool_length_unknown = true;
        if (!st.unknown_tool_warned) {
          st.unknown_tool_warned = true;
          spdlog::warn(
              "{}:{}: tool {} has no length in the tool table (G43 H{}): the tool-tip "
              "path does not depend on it, the tool_length column says unknown",
              st.file, b.ctx.line, h, h);
        }
      } else {
        b.ctx.fail(c.has('H') ? c.word('H') : tool_length->word,
                   fmt::format("tool {} has no length in the tool table (G43 H{})", h, h));
      }
    }
    st.g43 = true;
    st.tool_length_mm = length;
    new_tlo = length / st.unit();
  } else {
    st.g43 = false;
    st.tool_length_mm = 0.0;
    st.tool_length_unknown = false;
  }
  st.pos.z() -= new_tlo - st.tlo;
  st.tlo = new_tlo;
}

void convert_coord_system(ExecState& st, const BlockPlan& b) {
  if (const auto& g = b.codes.group(GGroup::coord_system)) {
    const Eigen::Vector3d old = st.g5x();
    st.coord_index = (g->code - gcode_id(54)) / 10;
    st.pos += old - st.g5x();
  }
}

void convert_path_control(ExecState& st, const BlockPlan& b) {
  const auto& g = b.codes.group(GGroup::path_control);
  if (!g) return;
  if (g->code == gcode_id(61)) {
    st.path_control = PathControl::exact_path;
  } else if (g->code == gcode_id(61, 1)) {
    st.path_control = PathControl::exact_stop;
  } else {
    st.path_control = PathControl::blending;
    const Word* p = b.codes.word('P');
    const Word* q = b.codes.word('Q');
    st.blend_tolerance = p ? p->value : 0.0;
    st.naive_cam_tolerance = q ? q->value : st.blend_tolerance;
  }
}

void convert_distance_modes(ExecState& st, const BlockPlan& b) {
  const BlockCodes& c = b.codes;
  if (const auto& g = c.group(GGroup::distance)) st.incremental = g->code == gcode_id(91);
  if (const auto& g = c.group(GGroup::arc_distance))
    st.arc_centre_absolute = g->code == gcode_id(90, 1);
  if (const auto& g = c.group(GGroup::retract)) st.retract_to_r = g->code == gcode_id(99);
}

void convert_axis_offsets(ExecState& st, const BlockPlan& b) {
  static constexpr char kAxisLetters[3] = {'X', 'Y', 'Z'};
  if (b.non_modal == gcode_id(92)) {
    for (int a = 0; a < 3; ++a)
      if (const Word* w = b.codes.word(kAxisLetters[a])) {
        st.g92[a] += st.pos[a] - w->value;
        st.pos[a] = w->value;
      }
    st.g92_saved = st.g92;
  } else if (b.non_modal == gcode_id(52)) {
    // LinuxCNC's G52 sets the same offset as G92, to the values written.
    for (int a = 0; a < 3; ++a)
      if (const Word* w = b.codes.word(kAxisLetters[a])) {
        st.pos[a] += st.g92[a] - w->value;
        st.g92[a] = w->value;
      }
    st.g92_saved = st.g92;
  } else if (b.non_modal == gcode_id(92, 1) || b.non_modal == gcode_id(92, 2)) {
    st.pos += st.g92;
    st.g92.setZero();
    if (b.non_modal == gcode_id(92, 1)) st.g92_saved.setZero();
  } else if (b.non_modal == gcode_id(92, 3)) {
    st.pos += st.g92 - st.g92_saved;
    st.g92 = st.g92_saved;
  }
}

void convert_stop(ExecState& st, const BlockPlan& b) {
  if (const auto& m = b.codes.group(MGroup::stopping))
    if (m->code == 2 || m->code == 30) st.ended = true;
}

}  // namespace abbe::gcode::detail
