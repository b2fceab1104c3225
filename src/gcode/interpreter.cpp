#include "abbe/gcode/interpreter.hpp"

#include <fmt/format.h>

#include <cmath>

#include "abbe/gcode/arc_geometry.hpp"
#include "abbe/gcode/canned_cycle.hpp"
#include "abbe/gcode/modal_groups.hpp"

namespace abbe::gcode {

namespace {

// Limits that keep one block from expanding into an unbounded number of
// motions (a typo such as L70000000 must be an error, not a hang).
constexpr double kMaxCycleRepeats = 100000;
constexpr double kMaxArcTurns = 10000;
constexpr double kMaxPecks = 100000;

constexpr double kMmPerInch = 25.4;

// gcode::plane_axes with names: the (first, second, normal) axes of the arc
// and canned-cycle plane.
struct PlaneAxes {
  int first, second, normal;
};

PlaneAxes named_axes(Plane plane) {
  const std::array<int, 3> a = plane_axes(plane);
  return {a[0], a[1], a[2]};
}

const char* plane_name(Plane plane) {
  switch (plane) {
    case Plane::xz:
      return "XZ";
    case Plane::yz:
      return "YZ";
    default:
      return "XY";
  }
}

constexpr char kAxisLetter[3] = {'X', 'Y', 'Z'};
constexpr char kCentreLetter[3] = {'I', 'J', 'K'};

bool is_cycle(int code) {
  return code == gcode_id(73) || code == gcode_id(81) || code == gcode_id(82) ||
         code == gcode_id(83) || code == gcode_id(85) || code == gcode_id(89);
}

bool is_integer(double v) { return std::abs(v - std::round(v)) < 1e-6; }

}  // namespace

// The modal state mirrors rs274ngc: positions and offsets are held in the
// program's current units and converted when G20/G21 switch, so that every
// decision (tolerances, peck loops) is taken on the same numbers.
struct Interpreter::State {
  InterpreterConfig config;
  std::string file;

  bool inch = false;
  bool incremental = false;
  bool arc_centre_absolute = false;  // G90.1
  Plane plane = Plane::xy;
  int motion_mode = gcode_id(80);
  bool retract_to_r = true;  // G99 (rs274ngc's start-up retract mode)

  // Program-frame position of the controlled point, program units: the
  // spindle nose s = (pos + g5x + g92 + tlo·e_z) in machine coordinates.
  Eigen::Vector3d pos = Eigen::Vector3d::Zero();
  int coord_index = 0;  // G54 = 0
  Eigen::Vector3d g92 = Eigen::Vector3d::Zero();
  Eigen::Vector3d g92_saved = Eigen::Vector3d::Zero();  // what G92.3 restores
  bool g43 = false;
  double tlo = 0.0;             // active tool length offset, program units (0 without G43)
  double tool_length_mm = 0.0;  // L of the G43 tool, mm

  double feed_mm = 0.0;  // mm/min
  double spindle = 0.0;
  int selected_tool = 0;
  int tool_in_spindle = 0;

  // Canned-cycle memory (program units).
  double cycle_r = 0.0, cycle_cc = 0.0, cycle_p = 0.0, cycle_q = 0.0;
  double cycle_initial_level = 0.0;
  bool cycle_initial_level_set = false;

  bool ended = false;

  double unit() const { return inch ? kMmPerInch : 1.0; }
  Eigen::Vector3d g5x() const {
    return config.work_offsets[static_cast<std::size_t>(coord_index)] / unit();
  }
  double active_length_mm() const { return g43 ? tool_length_mm : config.default_tool_length; }

  // Tool tip P (machine, mm) of a program-frame point. In mm the unit
  // factors are 1 and are left out (the same doubles, no divisions).
  Eigen::Vector3d tip(const Eigen::Vector3d& p) const {
    Eigen::Vector3d s;
    if (inch) {
      s = (p + g5x() + g92 + Eigen::Vector3d(0, 0, tlo)) * kMmPerInch;
    } else {
      s = p + config.work_offsets[static_cast<std::size_t>(coord_index)] + g92 +
          Eigen::Vector3d(0, 0, tlo);
    }
    s.z() -= active_length_mm();
    return s;
  }
};

Interpreter::Interpreter(InterpreterConfig config, std::string file)
    : state_(std::make_unique<State>()) {
  state_->config = std::move(config);
  state_->file = std::move(file);
  // Initial position is the tool tip; without G43 the program drives s = P + L·e_z.
  state_->pos = state_->config.initial_position - state_->config.work_offsets[0];
  state_->pos.z() += state_->config.default_tool_length;
}

Interpreter::~Interpreter() = default;
Interpreter::Interpreter(Interpreter&&) noexcept = default;
Interpreter& Interpreter::operator=(Interpreter&&) noexcept = default;

bool Interpreter::program_ended() const { return state_->ended; }
bool Interpreter::inch() const { return state_->inch; }
bool Interpreter::incremental() const { return state_->incremental; }
bool Interpreter::arc_centre_absolute() const { return state_->arc_centre_absolute; }
Plane Interpreter::plane() const { return state_->plane; }
bool Interpreter::retract_to_r() const { return state_->retract_to_r; }
Eigen::Vector3d Interpreter::program_position() const { return state_->pos; }
Eigen::Vector3d Interpreter::position() const { return state_->tip(state_->pos); }

void Interpreter::execute(const Block& block, std::string_view raw_line, const MotionSink& sink) {
  State& st = *state_;
  if (st.ended || block.words.empty()) return;
  const BlockContext ctx{st.file, block.line, raw_line};
  const BlockCodes c = classify_block(block, ctx);

  const auto& motion_code = c.group(GGroup::motion);
  const auto& non_modal = c.group(GGroup::non_modal);
  const int non_modal_code = non_modal ? non_modal->code : -1;
  const bool g92_axes = non_modal_code == gcode_id(92);
  const bool g53 = non_modal_code == gcode_id(53);
  const Word* first_axis = nullptr;
  for (char a : kAxisLetter)
    if (!first_axis && c.has(a)) first_axis = c.word(a);

  // The motion this block makes (rs274ngc: an explicit motion code, or the
  // modal one when axis words are present and nothing else uses them).
  int motion = -1;
  const Word* motion_word = nullptr;
  if (motion_code) {
    motion = motion_code->code;
    motion_word = motion_code->word;
    if (g92_axes && c.has_axis_word())
      ctx.fail(motion_word,
               fmt::format("cannot use two G codes that both use axis words ({} and G92)",
                           gcode_name(motion)));
  } else if (c.has_axis_word() && !g92_axes) {
    if (st.motion_mode == gcode_id(80))
      ctx.fail(first_axis, "axis words without a motion code (no motion mode is active)");
    motion = st.motion_mode;
    motion_word = first_axis;
  }
  if (motion == gcode_id(80) && c.has_axis_word() && !g92_axes)
    ctx.fail(first_axis, "axis words with G80 (canned cycle cancel)");
  if (g92_axes && !c.has_axis_word()) ctx.fail(non_modal->word, "G92 without axis words");

  // Words that need a code to use them (rs274ngc refuses them otherwise).
  const bool arc = motion == gcode_id(2) || motion == gcode_id(3);
  const bool cycle = is_cycle(motion);
  const auto& path = c.group(GGroup::path_control);
  const bool g64 = path && path->code == gcode_id(64);
  const bool g4 = non_modal_code == gcode_id(4);
  for (char letter : {'I', 'J', 'K'})
    if (c.has(letter) && !arc)
      ctx.fail(c.word(letter), fmt::format("{} word with no G2 or G3 to use it", letter));
  if (c.has('R') && !arc && !cycle)
    ctx.fail(c.word('R'), "R word with no G2, G3 or canned cycle to use it");
  if (c.has('P') && !arc && !g4 && !g64 && motion != gcode_id(82) && motion != gcode_id(89))
    ctx.fail(c.word('P'), "P word with no G2, G3, G4, G64, G82 or G89 to use it");
  if (c.has('Q') && !g64 && motion != gcode_id(73) && motion != gcode_id(83))
    ctx.fail(c.word('Q'), "Q word with no G64, G73 or G83 to use it");
  if (c.has('L') && !cycle) ctx.fail(c.word('L'), "L word with no canned cycle to use it");
  const auto& tool_length = c.group(GGroup::tool_length);
  if (c.has('H') && !(tool_length && tool_length->code == gcode_id(43)))
    ctx.fail(c.word('H'), "H word with no G43 to use it");

  std::uint32_t sub = 0;
  auto emit = [&](Motion& m) {
    m.line = block.line;
    m.sub = sub++;
    m.tool_length = st.active_length_mm();
    m.spindle = st.spindle;
    m.tool = st.selected_tool;
    sink(m);
  };

  // --- Execution order of rs274ngc ---
  // F, S, T
  if (const Word* f = c.word('F')) {
    if (f->value < 0) ctx.fail(f, "negative feed rate (F)");
    st.feed_mm = f->value * st.unit();
  }
  if (const Word* s = c.word('S')) {
    if (s->value < 0) ctx.fail(s, "negative spindle speed (S)");
    st.spindle = s->value;
  }
  if (const Word* t = c.word('T')) {
    if (t->value < 0 || !is_integer(t->value)) ctx.fail(t, "T word must be a non-negative integer");
    st.selected_tool = static_cast<int>(std::lround(t->value));
  }
  if (c.group(MGroup::tool_change)) st.tool_in_spindle = st.selected_tool;

  // G4 dwell
  if (g4) {
    const Word* p = c.word('P');
    if (!p) ctx.fail(non_modal->word, "dwell (G4) without a P word (seconds)");
    if (p->value < 0) ctx.fail(p, "negative dwell time (G4 P)");
    Motion m;
    m.kind = MotionKind::dwell;
    m.start = m.end = st.tip(st.pos);
    m.dwell_seconds = p->value;
    emit(m);
  }

  // Plane
  if (const auto& g = c.group(GGroup::plane)) {
    st.plane = g->code == gcode_id(17)   ? Plane::xy
               : g->code == gcode_id(18) ? Plane::xz
                                         : Plane::yz;
  }
  // Units: convert everything held in program units.
  if (const auto& g = c.group(GGroup::units)) {
    const bool inch = g->code == gcode_id(20);
    if (inch != st.inch) {
      const double k = inch ? 1.0 / kMmPerInch : kMmPerInch;
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
  }
  // Tool length offset: the spindle does not move, the program frame does.
  if (tool_length) {
    double new_tlo = 0.0;
    if (tool_length->code == gcode_id(43)) {
      int h = st.tool_in_spindle;
      if (const Word* hw = c.word('H')) {
        if (hw->value < 0 || !is_integer(hw->value))
          ctx.fail(hw, "H word must be a non-negative integer");
        h = static_cast<int>(std::lround(hw->value));
      }
      double length = 0.0;
      if (h != 0) {
        const auto it = st.config.tool_lengths.find(h);
        if (it == st.config.tool_lengths.end())
          ctx.fail(c.has('H') ? c.word('H') : tool_length->word,
                   fmt::format("tool {} has no length in the tool table (G43 H{})", h, h));
        length = it->second;
      }
      st.g43 = true;
      st.tool_length_mm = length;
      new_tlo = length / st.unit();
    } else {
      st.g43 = false;
      st.tool_length_mm = 0.0;
    }
    st.pos.z() -= new_tlo - st.tlo;
    st.tlo = new_tlo;
  }
  // Work coordinate system
  if (const auto& g = c.group(GGroup::coord_system)) {
    const Eigen::Vector3d old = st.g5x();
    st.coord_index = (g->code - gcode_id(54)) / 10;
    st.pos += old - st.g5x();
  }
  // Distance modes, retract mode
  if (const auto& g = c.group(GGroup::distance)) st.incremental = g->code == gcode_id(91);
  if (const auto& g = c.group(GGroup::arc_distance))
    st.arc_centre_absolute = g->code == gcode_id(90, 1);
  if (const auto& g = c.group(GGroup::retract)) st.retract_to_r = g->code == gcode_id(99);

  // G92 family
  if (non_modal_code == gcode_id(92)) {
    for (int a = 0; a < 3; ++a)
      if (const Word* w = c.word(kAxisLetter[a])) {
        st.g92[a] += st.pos[a] - w->value;
        st.pos[a] = w->value;
      }
    st.g92_saved = st.g92;
  } else if (non_modal_code == gcode_id(92, 1) || non_modal_code == gcode_id(92, 2)) {
    st.pos += st.g92;
    st.g92.setZero();
    if (non_modal_code == gcode_id(92, 1)) st.g92_saved.setZero();
  } else if (non_modal_code == gcode_id(92, 3)) {
    st.pos += st.g92 - st.g92_saved;
    st.g92 = st.g92_saved;
  }

  // Motion
  if (motion != -1) {
    if (!is_cycle(motion)) st.cycle_initial_level_set = false;
    if (g53) {
      if (motion != gcode_id(0) && motion != gcode_id(1))
        ctx.fail(non_modal->word, fmt::format("G53 needs G0 or G1, not {}", gcode_name(motion)));
      if (st.incremental) ctx.fail(non_modal->word, "G53 in incremental distance mode (G91)");
    }
    // End point in the program frame (rs274ngc's find_ends).
    Eigen::Vector3d end = st.pos;
    for (int a = 0; a < 3; ++a) {
      const Word* w = c.word(kAxisLetter[a]);
      if (!w) continue;
      if (g53) {
        const Eigen::Vector3d frame = st.g5x() + st.g92 + Eigen::Vector3d(0, 0, st.tlo);
        end[a] = w->value - frame[a];
      } else {
        end[a] = st.incremental ? st.pos[a] + w->value : w->value;
      }
    }

    if (motion == gcode_id(0) || motion == gcode_id(1)) {
      if (motion == gcode_id(1) && st.feed_mm == 0.0)
        ctx.fail(motion_word, "G1 with zero feed rate (no F word yet)");
      Motion m;
      m.kind = motion == gcode_id(0) ? MotionKind::rapid : MotionKind::linear;
      m.start = st.tip(st.pos);
      m.end = st.tip(end);
      m.feed = motion == gcode_id(0) ? 0.0 : st.feed_mm;
      st.pos = end;
      st.motion_mode = motion;
      emit(m);
    } else if (arc) {
      const char* gname = motion == gcode_id(2) ? "G2" : "G3";
      if (st.feed_mm == 0.0)
        ctx.fail(motion_word, fmt::format("arc ({}) with zero feed rate (no F word yet)", gname));
      const PlaneAxes ax = named_axes(st.plane);
      const bool ijk = c.has('I') || c.has('J') || c.has('K');
      if (!c.has('R') && !ijk)
        ctx.fail(motion_word, fmt::format("arc ({}) without I, J, K or R", gname));
      if (c.has('R') && ijk)
        ctx.fail(c.word('R'), fmt::format("arc ({}) with both R and I/J/K", gname));
      if (ijk) {
        const char off_plane = kCentreLetter[ax.normal];
        if (c.has(off_plane))
          ctx.fail(c.word(off_plane), fmt::format("{} word given for an arc in the {} plane",
                                                  off_plane, plane_name(st.plane)));
        if (st.arc_centre_absolute)
          for (int a : {ax.first, ax.second})
            if (!c.has(kCentreLetter[a]))
              ctx.fail(motion_word, fmt::format("{} word missing in absolute-centre arc (G90.1)",
                                                kCentreLetter[a]));
      } else if (!c.has(kAxisLetter[ax.first]) && !c.has(kAxisLetter[ax.second])) {
        ctx.fail(motion_word,
                 fmt::format("arc with no end point: {} and {} words missing for an "
                             "R-format arc in the {} plane",
                             kAxisLetter[ax.first], kAxisLetter[ax.second], plane_name(st.plane)));
      }
      int turns = 1;
      if (const Word* p = c.word('P')) {
        if (!is_integer(p->value))
          ctx.fail(p, fmt::format("P word (turns) of {} is not an integer", gname));
        if (p->value < 1.0)
          ctx.fail(p, fmt::format("P word (turns) of {} must be 1 or more", gname));
        if (p->value > kMaxArcTurns)
          ctx.fail(p, fmt::format("P word (turns) of {} is larger than {}", gname, kMaxArcTurns));
        turns = static_cast<int>(std::lround(p->value));
      }
      const Eigen::Vector2d start2(st.pos[ax.first], st.pos[ax.second]);
      const Eigen::Vector2d end2(end[ax.first], end[ax.second]);
      const ArcTolerances tol = arc_tolerances(st.inch);
      ArcCentre centre;
      if (ijk) {
        auto value = [&](int a) {
          return c.has(kCentreLetter[a]) ? c.word(kCentreLetter[a])->value : 0.0;
        };
        centre = arc_centre_ijk(start2, end2, Eigen::Vector2d(value(ax.first), value(ax.second)),
                                st.arc_centre_absolute, tol);
      } else {
        centre = arc_centre_r(start2, end2, c.word('R')->value, motion == gcode_id(2), tol);
      }
      if (!centre.error.empty()) ctx.fail(c.has('R') ? c.word('R') : motion_word, centre.error);
      Eigen::Vector3d centre3 = st.pos;
      centre3[ax.first] = centre.centre.x();
      centre3[ax.second] = centre.centre.y();
      Motion m;
      m.kind = MotionKind::arc;
      m.plane = st.plane;
      m.start = st.tip(st.pos);
      m.end = st.tip(end);
      m.center = st.tip(centre3);
      m.rotation = (motion == gcode_id(2) ? -1 : 1) * turns;
      m.feed = st.feed_mm;
      st.pos = end;
      st.motion_mode = motion;
      emit(m);
    } else if (cycle) {
      const std::string gname = gcode_name(motion);
      if (st.feed_mm == 0.0)
        ctx.fail(motion_word, fmt::format("canned cycle ({}) with zero feed rate", gname));
      const PlaneAxes ax = named_axes(st.plane);
      const bool continued = st.motion_mode == motion;
      double r_value = st.cycle_r;
      if (const Word* r = c.word('R'))
        r_value = r->value;
      else if (!continued)
        ctx.fail(motion_word, fmt::format("R plane missing for canned cycle {}", gname));
      int repeats = 1;
      if (const Word* l = c.word('L')) {
        if (!is_integer(l->value) || l->value < 1.0)
          ctx.fail(l,
                   fmt::format("L (repeats) of canned cycle {} must be a positive integer", gname));
        if (l->value > kMaxCycleRepeats)
          ctx.fail(l, fmt::format("L (repeats) of canned cycle {} is larger than {}", gname,
                                  kMaxCycleRepeats));
        repeats = static_cast<int>(std::lround(l->value));
      }
      const char cc_letter = kAxisLetter[ax.normal];
      if (!continued && !c.has(cc_letter))
        ctx.fail(motion_word, fmt::format("{} value missing for canned cycle {} in the {} plane",
                                          cc_letter, gname, plane_name(st.plane)));
      const double cc_value = c.has(cc_letter) ? c.word(cc_letter)->value : st.cycle_cc;
      CannedCycle cyc;
      cyc.code = motion;
      cyc.current = Eigen::Vector3d(st.pos[ax.first], st.pos[ax.second], st.pos[ax.normal]);
      if (!st.cycle_initial_level_set) {
        st.cycle_initial_level = cyc.current.z();
        st.cycle_initial_level_set = true;
      }
      cyc.initial_level = st.cycle_initial_level;
      const Word* wa = c.word(kAxisLetter[ax.first]);
      const Word* wb = c.word(kAxisLetter[ax.second]);
      if (st.incremental) {
        cyc.hole = cyc.current.head<2>();
        cyc.increment = Eigen::Vector2d(wa ? wa->value : 0.0, wb ? wb->value : 0.0);
        cyc.r = r_value + cyc.initial_level;
        cyc.bottom = cyc.r + cc_value;
      } else {
        cyc.hole =
            Eigen::Vector2d(wa ? wa->value : cyc.current.x(), wb ? wb->value : cyc.current.y());
        cyc.r = r_value;
        cyc.bottom = cc_value;
      }
      if (cyc.r < cyc.bottom)
        ctx.fail(c.has('R') ? c.word('R') : motion_word,
                 fmt::format("R plane below the hole bottom in canned cycle {} (R < {})", gname,
                             cc_letter));
      cyc.retract_to_r = st.retract_to_r;
      cyc.repeats = repeats;
      if (motion == gcode_id(82) || motion == gcode_id(89)) {
        if (!continued && !c.has('P'))
          ctx.fail(motion_word, fmt::format("dwell time (P) missing for canned cycle {}", gname));
        cyc.dwell = c.has('P') ? c.word('P')->value : st.cycle_p;
        st.cycle_p = cyc.dwell;
      }
      if (motion == gcode_id(73) || motion == gcode_id(83)) {
        if (!continued && !c.has('Q'))
          ctx.fail(motion_word, fmt::format("peck depth (Q) missing for canned cycle {}", gname));
        cyc.peck = c.has('Q') ? c.word('Q')->value : st.cycle_q;
        if (cyc.peck <= 0.0)
          ctx.fail(c.has('Q') ? c.word('Q') : motion_word,
                   fmt::format("peck depth (Q) of canned cycle {} must be positive", gname));
        st.cycle_q = cyc.peck;
        if ((cyc.r - cyc.bottom) / cyc.peck > kMaxPecks)
          ctx.fail(c.has('Q') ? c.word('Q') : motion_word,
                   fmt::format("peck depth (Q) of canned cycle {} is so small that the hole "
                               "would take more than {} pecks",
                               gname, kMaxPecks));
      }
      cyc.peck_clearance = st.inch ? 0.010 : 0.010 * kMmPerInch;

      auto to_program = [&](const Eigen::Vector3d& abc) {
        Eigen::Vector3d p;
        p[ax.first] = abc.x();
        p[ax.second] = abc.y();
        p[ax.normal] = abc.z();
        return p;
      };
      const Eigen::Vector3d final_abc = expand_canned_cycle(cyc, [&](const CycleStep& step) {
        const Eigen::Vector3d target = to_program(step.target);
        Motion m;
        if (step.kind == CycleStep::Kind::dwell) {
          m.kind = MotionKind::dwell;
          m.start = m.end = st.tip(target);
          m.dwell_seconds = step.seconds;
        } else {
          m.kind = step.kind == CycleStep::Kind::feed ? MotionKind::linear : MotionKind::rapid;
          m.start = st.tip(st.pos);
          m.end = st.tip(target);
          m.feed = step.kind == CycleStep::Kind::feed ? st.feed_mm : 0.0;
          st.pos = target;
        }
        emit(m);
      });
      st.pos = to_program(final_abc);
      st.cycle_cc = cc_value;
      st.cycle_r = r_value;
      st.motion_mode = motion;
    } else if (motion == gcode_id(80)) {
      st.motion_mode = motion;
    }
  }

  // Program stops
  if (const auto& m = c.group(MGroup::stopping))
    if (m->code == 2 || m->code == 30) st.ended = true;
}

}  // namespace abbe::gcode
