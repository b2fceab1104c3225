// convert_motion: the end point of the block (rs274ngc's find_ends) and the
// straight, arc and canned-cycle motions.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string_view>

#include "abbe/gcode/arc_geometry.hpp"
#include "abbe/gcode/canned_cycle.hpp"
#include "abbe/gcode/motion_limits.hpp"
#include "interpreter_steps.hpp"

namespace abbe::gcode::detail {
namespace {

// Limits that keep one block from expanding into an unbounded number of
// motions (a typo such as L70000000 must be an error, not a hang).
constexpr double kMaxCycleRepeats = 100000;
constexpr double kMaxArcTurns = 10000;
constexpr double kMaxPecks = 100000;

constexpr char kAxisLetter[3] = {'X', 'Y', 'Z'};
constexpr char kCentreLetter[3] = {'I', 'J', 'K'};

// gcode::plane_axes with names: the (first, second, normal) axes of the arc
// and canned-cycle plane.
struct PlaneAxes {
  int first, second, normal;
};

PlaneAxes named_axes(Plane plane) {
  const std::array<int, 3> a = plane_axes(plane);
  return {a[0], a[1], a[2]};
}

// A feed move needs a feed rate: an F word in its block in G93 (rs274ngc),
// a spindle speed in G95.
void check_feed_rules(const ExecState& st, const BlockPlan& b, const char* gname) {
  if (st.feed_mode == FeedMode::inverse_time) {
    if (!b.codes.has('F'))
      b.ctx.fail(b.motion_word,
                 fmt::format("F word missing in inverse-time feed mode (G93) for {}", gname));
    if (st.feed_mm == 0.0)
      b.ctx.fail(b.codes.word('F'), fmt::format("zero inverse-time feed rate (G93) for {}", gname));
    return;
  }
  if (st.feed_mm == 0.0) {
    if (gname[1] == '1') b.ctx.fail(b.motion_word, "G1 with zero feed rate (no F word yet)");
    b.ctx.fail(b.motion_word, fmt::format("arc ({}) with zero feed rate (no F word yet)", gname));
  }
  if (st.feed_mode == FeedMode::units_per_rev && st.spindle == 0.0)
    b.ctx.fail(b.motion_word,
               fmt::format("{} in feed per revolution mode (G95) with spindle speed 0", gname));
}

// The usual case (units per minute, a feed rate set) without a call.
inline void check_feed(const ExecState& st, const BlockPlan& b, const char* gname) {
  if (st.feed_mode != FeedMode::units_per_minute || st.feed_mm == 0.0)
    check_feed_rules(st, b, gname);
}

// Polar words (rs274ngc): @ the radius, ^ the angle in degrees, about the
// program origin in X, Y. G90: the missing one is the current point's; G91:
// both add to the current point's (indeterminate at the origin).
void polar_end(const ExecState& st, const BlockPlan& b, bool g53, Eigen::Vector3d& end) {
  const BlockCodes& c = b.codes;
  const Word* radius = c.word('@');
  const Word* angle = c.word('^');
  const Word* first = radius ? radius : angle;
  for (char a : {'X', 'Y'})
    if (c.has(a))
      b.ctx.fail(c.word(a),
                 fmt::format("cannot give both polar coordinates (@, ^) and an {} word", a));
  if (g53) b.ctx.fail(first, "polar coordinates (@, ^) with G53 are not supported");
  if (is_cycle(b.motion) && st.plane != Plane::xy)
    b.ctx.fail(first, fmt::format("polar coordinates (@, ^) with a canned cycle in the {} plane "
                                  "are not supported",
                                  plane_name(st.plane)));
  const double x = st.pos.x();
  const double y = st.pos.y();
  double r = std::hypot(x, y);
  double degrees = std::atan2(y, x) * 180.0 / M_PI;
  if (st.incremental) {
    if (x == 0.0 && y == 0.0)
      b.ctx.fail(first,
                 "incremental polar coordinates (G91 with @ or ^) are indeterminate at the origin");
    if (radius) r += radius->value;
    if (angle) degrees += angle->value;
  } else {
    if (radius && !angle && x == 0.0 && y == 0.0)
      b.ctx.fail(first, "polar coordinates at the origin need the angle (^)");
    if (radius) r = radius->value;
    if (angle) degrees = angle->value;
  }
  const double rad = degrees * M_PI / 180.0;
  end.x() = r * std::cos(rad);
  end.y() = r * std::sin(rad);
}

}  // namespace

// The end point, the straight motion and the delivery are written once, as
// always-inline bodies: the plain block's path (convert_plain_motion, most
// of a CAM program) gets them in one function; the general path calls them
// through motion_end, straight_motion and deliver_motion below.
[[gnu::always_inline]] static inline Eigen::Vector3d inline_motion_end(ExecState& st,
                                                                       const BlockPlan& b) {
  const int motion = b.motion;
  const BlockCodes& c = b.codes;
  const bool g53 = b.non_modal == gcode_id(53);
  if (g53) {
    const Word* at = c.group(GGroup::non_modal)->word;
    if (motion != gcode_id(0) && motion != gcode_id(1))
      b.ctx.fail(at, fmt::format("G53 needs G0 or G1, not {}", gcode_name(motion)));
    if (st.incremental) b.ctx.fail(at, "G53 in incremental distance mode (G91)");
  }
  // End point in the program frame (rs274ngc's find_ends).
  Eigen::Vector3d end = st.pos;
  if (c.has_polar_word()) polar_end(st, b, g53, end);
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
  return end;
}

[[gnu::always_inline]] static inline Motion inline_straight_motion(ExecState& st,
                                                                   const BlockPlan& b,
                                                                   const Eigen::Vector3d& end) {
  const bool rapid = b.motion == gcode_id(0);
  if (!rapid) check_feed(st, b, "G1");
  Motion m;
  m.kind = rapid ? MotionKind::rapid : MotionKind::linear;
  m.start = st.tip(st.pos);
  m.end = st.tip(end);
  // The length matters only to inverse-time feed (no square root otherwise).
  m.feed = rapid                                    ? 0.0
           : st.feed_mode == FeedMode::inverse_time ? st.feed_rate_mm((m.end - m.start).norm())
                                                    : st.feed_rate_mm(0.0);
  st.motion_mode = b.motion;
  return m;
}

void note_motion_code(ExecState& st, int motion) {
  if (!is_cycle(motion)) st.cycle_initial_level_set = false;
  if (motion >= gcode_id(0) && motion <= gcode_id(3)) st.fanuc_group01 = motion;
}

// The word a refused motion is reported at: the first axis, centre or radius word.
static const Word* motion_anchor(const Block& block) {
  for (const auto& w : block.words)
    if (std::string_view("XYZIJKR@^").find(w.letter) != std::string_view::npos) return &w;
  return block.words.empty() ? nullptr : &block.words.front();
}

void stamp_motion(const ExecState& st, Motion& m, std::size_t line, std::uint32_t sub) {
  m.line = line;
  m.sub = sub;
  m.tool_length = st.g43 && st.tool_length_unknown ? std::numeric_limits<double>::quiet_NaN()
                                                   : st.active_length_mm();
  m.spindle = st.spindle;
  m.tool = st.selected_tool;
}

[[gnu::always_inline]] static inline void inline_deliver_motion(ExecState& st, Motion& m,
                                                                const Block& block,
                                                                const BlockContext& ctx,
                                                                const MotionSink& sink) {
  double far = std::max(m.start.cwiseAbs().maxCoeff(), m.end.cwiseAbs().maxCoeff());
  if (m.kind == MotionKind::arc) far = std::max(far, m.center.cwiseAbs().maxCoeff());
  if (!(far <= kMaxCoordinateMm))
    ctx.fail(motion_anchor(block), fmt::format("the motion reaches a coordinate of {:g} mm, "
                                               "beyond the bound of ±{:g} mm",
                                               far, kMaxCoordinateMm));
  ++st.delivered;
  try {
    sink(m);
  } catch (const MotionRefused& e) {
    ctx.fail(motion_anchor(block), e.what());
  }
}

Eigen::Vector3d motion_end(ExecState& st, const BlockPlan& b) { return inline_motion_end(st, b); }

Motion straight_motion(ExecState& st, const BlockPlan& b, const Eigen::Vector3d& end) {
  return inline_straight_motion(st, b, end);
}

void deliver_motion(ExecState& st, Motion& m, const Block& block, const BlockContext& ctx,
                    const MotionSink& sink) {
  inline_deliver_motion(st, m, block, ctx, sink);
}

// In the same file as motion_end, straight_motion and deliver_motion, so
// that the plain block's one motion is made in one function.
void convert_plain_motion(ExecState& st, const BlockPlan& b, const Block& block,
                          const MotionSink& sink) {
  note_motion_code(st, b.motion);
  const Eigen::Vector3d end = inline_motion_end(st, b);
  if (b.motion == gcode_id(2) || b.motion == gcode_id(3)) {
    auto emit_arc = [&](Motion& m) {
      stamp_motion(st, m, block.line, 0);
      deliver_motion(st, m, block, b.ctx, sink);
    };
    convert_arc(st, b, end, make_hook(emit_arc));
    return;
  }
  Motion m = inline_straight_motion(st, b, end);
  st.pos = end;
  stamp_motion(st, m, block.line, 0);
  inline_deliver_motion(st, m, block, b.ctx, sink);
}

void convert_motion(ExecState& st, const BlockPlan& b, const Emit& emit) {
  const int motion = b.motion;
  if (motion == -1) return;
  note_motion_code(st, motion);
  const Eigen::Vector3d end = motion_end(st, b);
  if (motion == gcode_id(0) || motion == gcode_id(1)) {
    convert_straight(st, b, end, emit);
  } else if (motion == gcode_id(2) || motion == gcode_id(3)) {
    convert_arc(st, b, end, emit);
  } else if (is_cycle(motion)) {
    convert_cycle(st, b, emit);
  } else if (motion == gcode_id(80)) {
    st.motion_mode = st.config.dialect.dialect == Dialect::fanuc ? st.fanuc_group01 : gcode_id(80);
  }
}

void convert_straight(ExecState& st, const BlockPlan& b, const Eigen::Vector3d& end,
                      const Emit& emit) {
  Motion m = straight_motion(st, b, end);
  if (st.comp.offsetting()) {  // the tool centre path (cutter_comp.cpp)
    st.stamp(m);
    comp_straight(st, b, end, m);
    return;
  }
  st.pos = end;
  emit(m);
}

void convert_arc(ExecState& st, const BlockPlan& b, const Eigen::Vector3d& end, const Emit& emit) {
  const BlockCodes& c = b.codes;
  const BlockContext& ctx = b.ctx;
  const int motion = b.motion;
  const Word* motion_word = b.motion_word;
  const char* gname = motion == gcode_id(2) ? "G2" : "G3";
  check_feed(st, b, gname);
  const PlaneAxes ax = named_axes(st.plane);
  const bool ijk = c.has('I') || c.has('J') || c.has('K');
  if (!c.has('R') && !ijk)
    ctx.fail(motion_word, fmt::format("arc ({}) without I, J, K or R", gname));
  if (c.has('R') && ijk)
    ctx.fail(c.word('R'), fmt::format("arc ({}) with both R and I/J/K", gname));
  if (ijk) {
    const char off_plane = kCentreLetter[ax.normal];
    if (c.has(off_plane))
      ctx.fail(c.word(off_plane), fmt::format("{} word given for an arc in the {} plane", off_plane,
                                              plane_name(st.plane)));
    if (st.arc_centre_absolute)
      for (int a : {ax.first, ax.second})
        if (!c.has(kCentreLetter[a]))
          ctx.fail(motion_word,
                   fmt::format("{} word missing in absolute-centre arc (G90.1)", kCentreLetter[a]));
  } else if (!c.has(kAxisLetter[ax.first]) && !c.has(kAxisLetter[ax.second]) &&
             !c.has_polar_word()) {
    ctx.fail(motion_word,
             fmt::format("arc with no end point: {} and {} words missing for an "
                         "R-format arc in the {} plane",
                         kAxisLetter[ax.first], kAxisLetter[ax.second], plane_name(st.plane)));
  }
  int turns = 1;
  if (const Word* p = c.word('P')) {
    if (!is_integer(p->value))
      ctx.fail(p, fmt::format("P word (turns) of {} is not an integer", gname));
    if (p->value < 1.0) ctx.fail(p, fmt::format("P word (turns) of {} must be 1 or more", gname));
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
  if (st.feed_mode == FeedMode::inverse_time) {
    // The length of the helix: sweep · radius in the plane, the normal axis linear.
    const Eigen::Vector2d s0 = start2 - centre.centre;
    const Eigen::Vector2d e0 = end2 - centre.centre;
    double sweep = std::atan2(s0.x() * e0.y() - s0.y() * e0.x(), s0.dot(e0));
    if (motion == gcode_id(2)) sweep = -sweep;
    if (sweep < 1e-6) sweep += units::kTwoPi;
    sweep += units::kTwoPi * (turns - 1);
    const double planar = 0.5 * (s0.norm() + e0.norm()) * sweep * st.unit();
    m.feed = st.feed_rate_mm(std::hypot(planar, (end[ax.normal] - st.pos[ax.normal]) * st.unit()));
  } else {
    m.feed = st.feed_rate_mm(0.0);
  }
  st.motion_mode = motion;
  if (st.comp.offsetting()) {  // the tool centre path (cutter_comp.cpp)
    st.stamp(m);
    comp_arc(st, b, end, centre.centre, m);
    return;
  }
  st.pos = end;
  emit(m);
}

void convert_cycle(ExecState& st, const BlockPlan& b, const Emit& emit) {
  const BlockCodes& c = b.codes;
  const BlockContext& ctx = b.ctx;
  const int motion = b.motion;
  const Word* motion_word = b.motion_word;
  const std::string gname = gcode_name(motion);
  if (st.feed_mode == FeedMode::inverse_time)
    ctx.fail(motion_word, fmt::format("canned cycle ({}) in inverse-time feed mode (G93)", gname));
  if (st.feed_mm == 0.0)
    ctx.fail(motion_word, fmt::format("canned cycle ({}) with zero feed rate", gname));
  if (st.feed_rate_mm(0.0) == 0.0)
    ctx.fail(
        motion_word,
        fmt::format("canned cycle ({}) in feed per revolution (G95) with spindle speed 0", gname));
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
      ctx.fail(l, fmt::format("L (repeats) of canned cycle {} must be a positive integer", gname));
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
  const Word* polar_r = c.word('@');
  const Word* polar_a = c.word('^');
  if (st.incremental) {
    cyc.hole = cyc.current.head<2>();
    cyc.increment = Eigen::Vector2d(wa ? wa->value : 0.0, wb ? wb->value : 0.0);
    if (polar_r || polar_a) {
      // rs274ngc: each repeat turns the hole about the program origin.
      cyc.radius_increment = polar_r ? polar_r->value : 0.0;
      cyc.angle_increment = polar_a ? polar_a->value * M_PI / 180.0 : 0.0;
      double aa = cyc.hole.x();
      double bb = cyc.hole.y();
      for (int k = 0; k < repeats; ++k) {
        if (aa == 0.0 && bb == 0.0)
          ctx.fail(polar_r ? polar_r : polar_a,
                   "incremental polar coordinates (G91 with @ or ^) are indeterminate at the "
                   "origin");
        const double radius = std::hypot(bb, aa) + cyc.radius_increment;
        const double theta = std::atan2(bb, aa);
        aa = radius * std::cos(theta);
        bb = radius * std::sin(theta);
        if (cyc.angle_increment != 0.0 && aa == 0.0 && bb == 0.0)
          ctx.fail(polar_r ? polar_r : polar_a,
                   "incremental polar coordinates (G91 with @ or ^) are indeterminate at the "
                   "origin");
      }
    }
    cyc.r = r_value + cyc.initial_level;
    cyc.bottom = cyc.r + cc_value;
  } else if (polar_r || polar_a) {
    // G17 (others are refused): the hole from the polar words about the
    // program origin, the missing one from where the tool stands.
    const double radius = polar_r ? polar_r->value : std::hypot(st.pos.y(), st.pos.x());
    const double theta =
        polar_a ? polar_a->value * M_PI / 180.0 : std::atan2(st.pos.y(), st.pos.x());
    cyc.hole = Eigen::Vector2d(radius * std::cos(theta), radius * std::sin(theta));
    cyc.r = r_value;
    cyc.bottom = cc_value;
  } else {
    cyc.hole = Eigen::Vector2d(wa ? wa->value : cyc.current.x(), wb ? wb->value : cyc.current.y());
    cyc.r = r_value;
    cyc.bottom = cc_value;
  }
  if (cyc.r < cyc.bottom)
    ctx.fail(
        c.has('R') ? c.word('R') : motion_word,
        fmt::format("R plane below the hole bottom in canned cycle {} (R < {})", gname, cc_letter));
  cyc.retract_to_r = st.retract_to_r;
  cyc.repeats = repeats;
  if (motion == gcode_id(84) && st.spindle_direction != 1)
    ctx.fail(motion_word, "spindle not turning clockwise (M3) in tapping cycle G84");
  if (motion == gcode_id(74) && st.spindle_direction != -1)
    ctx.fail(motion_word, "spindle not turning counter-clockwise (M4) in tapping cycle G74");
  if (motion == gcode_id(74) || motion == gcode_id(84))
    cyc.dwell = c.has('P') ? c.word('P')->value : 0.0;
  if (motion == gcode_id(82) || motion == gcode_id(86) || motion == gcode_id(89)) {
    if (!continued && !c.has('P'))
      ctx.fail(motion_word, fmt::format("dwell time (P) missing for canned cycle {}", gname));
    cyc.dwell = c.has('P') ? c.word('P')->value : st.cycle_p;
    st.cycle_p = cyc.dwell;
  }
  if (motion == gcode_id(87)) {
    // rs274ngc: I, J and K in every G87 block (they are not modal), the
    // spindle turning; abbe takes the XY plane only.
    if (st.plane != Plane::xy)
      ctx.fail(motion_word, "back boring (G87) is supported in the XY plane (G17) only");
    for (char letter : {'I', 'J', 'K'})
      if (!c.has(letter))
        ctx.fail(motion_word, fmt::format("{} word missing for back boring (G87)", letter));
    if (st.spindle_direction == 0)
      ctx.fail(motion_word, "spindle not turning in back boring cycle G87");
    cyc.shift = Eigen::Vector2d(c.word('I')->value, c.word('J')->value);
    const double k = c.word('K')->value;
    cyc.back_bore_level = st.incremental ? cyc.bottom + k : k;
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
  // rs274ngc's G73/G83 retract: 0.010 inch.
  cyc.peck_clearance = st.inch ? 0.010 : 0.010 * units::kMmPerInch;

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
      m.feed = step.kind == CycleStep::Kind::feed ? st.feed_rate_mm(0.0) : 0.0;
      st.pos = target;
    }
    emit(m);
  });
  st.pos = to_program(final_abc);
  st.cycle_cc = cc_value;
  st.cycle_r = r_value;
  st.motion_mode = motion;
}

}  // namespace abbe::gcode::detail
