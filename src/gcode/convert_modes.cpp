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
    st.feed_mm = st.f_word = 0.0;
  st.feed_mode = mode;
}

void convert_feed_speed_tool(ExecState& st, const BlockPlan& b) {
  const BlockCodes& c = b.codes;
  if (const Word* f = c.word('F')) {
    if (f->value < 0) b.ctx.fail(f, "negative feed rate (F)");
    st.feed_mm = st.feed_mode == FeedMode::inverse_time ? f->value : f->value * st.unit();
    st.f_word = f->value;
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
  if (const auto& m = c.group(MGroup::tool_change)) {
    if (m->code == 61) {
      // M61 Q: the tool in the spindle is Q, without a tool change.
      const Word* q = c.word('Q');
      if (!q || q->value < 0)
        b.ctx.fail(q ? q : m->word, "M61 needs a non-negative Q word (the tool number)");
      if (!is_integer(q->value)) b.ctx.fail(q, "Q word of M61 (tool number) is not an integer");
      if (q->value > 99999.0) b.ctx.fail(q, "Q word of M61 (tool number) is above 99999");
      st.selected_tool = st.tool_in_spindle = static_cast<int>(std::lround(q->value));
    } else {
      st.tool_in_spindle = st.selected_tool;
      // rs274ngc reads the position back after a tool change: after G40 the
      // tool is at the compensated point, and the program goes on from there.
      if (st.comp.exit_pending) {
        st.pos = st.program_of_nose(st.comp.exit_nose_mm);
        st.comp.exit_pending = false;
      }
    }
  }
  if (const auto& m = c.group(MGroup::spindle))
    st.spindle_direction = m->code == 3 ? 1 : m->code == 4 ? -1 : 0;
  if (const auto& m = c.group(MGroup::coolant)) {
    if (m->code == 7) st.mist = true;
    if (m->code == 8) st.flood = true;
    if (m->code == 9) st.mist = st.flood = false;
  }
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
  set_units(st, g->code == gcode_id(20));
}

void set_units(ExecState& st, bool inch) {
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

namespace {

// The length of tool h from the tool table (mm); a tool without one is an
// error or, where the configuration allows it, 0 reported as unknown.
double table_length(ExecState& st, const BlockContext& ctx, const Word* at, int h) {
  st.tool_length_unknown = false;
  if (h == 0) return 0.0;
  const auto it = st.config.tool_lengths.find(h);
  if (it != st.config.tool_lengths.end()) return it->second;
  if (!st.config.allow_unknown_tool_length)
    ctx.fail(at, fmt::format("tool {} has no length in the tool table (G43 H{})", h, h));
  // The tip path does not depend on L while G43 is active (s - L with
  // s = P + L): taken as 0, reported unknown.
  st.tool_length_unknown = true;
  if (!st.unknown_tool_warned) {
    st.unknown_tool_warned = true;
    spdlog::warn(
        "{}:{}: tool {} has no length in the tool table (G43 H{}): the tool-tip "
        "path does not depend on it, the tool_length column says unknown",
        st.file, ctx.line, h, h);
  }
  return 0.0;
}

// The spindle does not move, the program frame does.
void set_tool_offset(ExecState& st, bool on, double length_mm) {
  st.g43 = on;
  st.tool_length_mm = on ? length_mm : 0.0;
  if (!on) st.tool_length_unknown = false;
  const double new_tlo = st.tool_length_mm / st.unit();
  st.pos.z() -= new_tlo - st.tlo;
  st.tlo = new_tlo;
}

}  // namespace

void convert_tool_length(ExecState& st, const BlockPlan& b) {
  const BlockCodes& c = b.codes;
  const auto& tool_length = c.group(GGroup::tool_length);
  if (!tool_length) return;
  if (tool_length->code == gcode_id(43)) {
    int h = st.tool_in_spindle;
    if (const Word* hw = c.word('H')) {
      if (hw->value < 0 || !is_integer(hw->value))
        b.ctx.fail(hw, "H word must be a non-negative integer");
      if (hw->value > 99999.0) b.ctx.fail(hw, "H word (tool number) is above 99999");
      h = static_cast<int>(std::lround(hw->value));
    }
    const double length = table_length(st, b.ctx, c.has('H') ? c.word('H') : tool_length->word, h);
    set_tool_offset(st, true, length);
  } else if (tool_length->code == gcode_id(43, 1)) {
    // Dynamic tool length offset: the Z word is the tool length (program units).
    for (char a : {'X', 'Y'})
      if (c.has(a))
        b.ctx.fail(c.word(a), fmt::format("a tool offset along {} (G43.1 {}) is not supported "
                                          "(abbe's tool lies along Z)",
                                          a, a));
    const Word* z = c.word('Z');
    st.tool_length_unknown = false;
    set_tool_offset(st, true, z ? z->value * st.unit() : 0.0);
  } else if (tool_length->code == gcode_id(43, 2)) {
    // Additional offset (rs274ngc): the length of tool H, or the Z word,
    // added to the offset in force (0 without G43).
    const Word* hw = c.word('H');
    if (hw && c.has_axis_word())
      b.ctx.fail(tool_length->word, "G43.2 cannot have both an H word and axis words");
    if (!hw && !c.has_axis_word())
      b.ctx.fail(tool_length->word, "G43.2 needs an H word (a tool) or a Z word (a length)");
    for (char a : {'X', 'Y'})
      if (c.has(a))
        b.ctx.fail(c.word(a), fmt::format("a tool offset along {} (G43.2 {}) is not supported "
                                          "(abbe's tool lies along Z)",
                                          a, a));
    const bool was_unknown = st.g43 && st.tool_length_unknown;
    double add = 0.0;
    if (hw) {
      if (hw->value < 0 || !is_integer(hw->value))
        b.ctx.fail(hw, "H word must be a non-negative integer");
      if (hw->value > 99999.0) b.ctx.fail(hw, "H word (tool number) is above 99999");
      add = table_length(st, b.ctx, hw, static_cast<int>(std::lround(hw->value)));
    } else if (const Word* z = c.word('Z')) {
      add = z->value * st.unit();
      st.tool_length_unknown = false;
    }
    st.tool_length_unknown = st.tool_length_unknown || was_unknown;
    set_tool_offset(st, true, (st.g43 ? st.tool_length_mm : 0.0) + add);
  } else {
    set_tool_offset(st, false, 0.0);
  }
}

void convert_modal_save(ExecState& st, const BlockPlan& b) {
  const auto& m = b.codes.group(MGroup::modal_save);
  if (!m) return;
  SaveSlot& slot = st.save_slots.back();
  if (m->code == 70 || m->code == 73) {
    SavedModes& s = slot.modes;
    s.inch = st.inch;
    s.incremental = st.incremental;
    s.arc_centre_absolute = st.arc_centre_absolute;
    s.plane = st.plane;
    s.feed_mode = st.feed_mode;
    s.feed_mm = st.feed_mm;
    s.coord_index = st.coord_index;
    s.g43 = st.g43;
    s.retract_to_r = st.retract_to_r;
    s.path_control = st.path_control;
    s.blend_tolerance = st.blend_tolerance;
    s.naive_cam_tolerance = st.naive_cam_tolerance;
    s.spindle = st.spindle;
    s.spindle_direction = st.spindle_direction;
    slot.valid = true;
    slot.autorestore = m->code == 73;
  } else if (m->code == 71) {
    slot.valid = false;
  } else {  // M72
    if (!slot.valid)
      b.ctx.fail(m->word,
                 "M72 without a state saved by M70 or M73 at this call level (or after M71)");
    restore_modes(st, slot.modes, b.ctx, m->word);
  }
}

void restore_modes(ExecState& st, const SavedModes& saved, const BlockContext& ctx,
                   const Word* at) {
  set_units(st, saved.inch);
  st.incremental = saved.incremental;
  st.arc_centre_absolute = saved.arc_centre_absolute;
  st.plane = saved.plane;
  st.feed_mode = saved.feed_mode;
  st.feed_mm = saved.feed_mm;
  st.f_word = st.feed_mode == FeedMode::inverse_time ? st.feed_mm : st.feed_mm / st.unit();
  const Eigen::Vector3d old = st.g5x();
  st.coord_index = saved.coord_index;
  st.pos += old - st.g5x();
  // rs274ngc re-executes G43 (the tool in the spindle) or G49.
  set_tool_offset(st, saved.g43, saved.g43 ? table_length(st, ctx, at, st.tool_in_spindle) : 0.0);
  st.retract_to_r = saved.retract_to_r;
  st.path_control = saved.path_control;
  st.blend_tolerance = saved.blend_tolerance;
  st.naive_cam_tolerance = saved.naive_cam_tolerance;
  st.spindle = saved.spindle;
  st.spindle_direction = saved.spindle_direction;
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
  if (const auto& m = b.codes.group(MGroup::stopping)) {
    comp_flush(st);  // rs274ngc: a stop hands on what compensation holds back
    if (m->code == 2 || m->code == 30) st.ended = true;
  }
}

}  // namespace abbe::gcode::detail
