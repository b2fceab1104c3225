// Cutter radius compensation (G40, G41, G42, G41.1, G42.1) with the
// semantics of LinuxCNC 2.9's rs274ngc (read in its interp_convert.cc and
// interp_queue.cc, checked against its rs274): the tool centre runs at the
// radius to the left (G41) or right (G42) of the programmed XY path.
//
// - The first move after G41/G42 (the entry move) is a straight line that
//   ends at the radius from the programmed end, perpendicular to the move;
//   it must be longer than the radius. An entry arc ends at the radius
//   along its normal, with a new centre so that it stays a circular arc.
// - Each later move is offset along its own normal. Where two moves meet at
//   an outside corner an arc about the programmed corner joins them (a
//   rapid for G0); at an inside corner the previous move's end is moved
//   back to where the two offset paths meet. rs274ngc's angle tolerance for
//   "no corner" is 0.05 rad.
// - So a move is only final once the next one is known: compensated motions
//   wait in a queue (with the dwells between them) and are handed on when
//   the next XY move places their end, at G40, at M0/M1/M2/M30/M60 and at
//   the end of the program (Interpreter::finish).
// - rs274ngc's errors for impossible geometry are abbe errors at the block
//   that finds them: an entry move not longer than the radius, a tool radius
//   not below the radius of an arc the tool is inside, inside corners the
//   tool cannot reach without gouging (the moved end would run backwards).
// - G17 and G18 (in the plane's axes Z, X; lathe tool orientations are not
//   modelled: G41.1/G42.1 L is refused), not G19; every frame change while
//   it is on is refused (units, plane, offsets, tool length, tool).
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <array>
#include <cmath>

#include "abbe/gcode/arc_geometry.hpp"
#include "interpreter_steps.hpp"

namespace abbe::gcode::detail {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kHalfPi = kPi / 2.0;
constexpr double kSmall = 0.05;  // rs274ngc's TOLERANCE_CONCAVE_CORNER (radians)

bool left(const CutterComp& c) { return c.side > 0; }
// rs274ngc's TOOL_INSIDE_ARC: the tool is on the centre's side of the arc.
bool tool_inside_arc(int side, int turn) {
  return (side > 0 && turn > 0) || (side < 0 && turn < 0);
}

// rs274ngc's find_turn: the signed sweep (radians) from p1 to p2 about c.
double find_turn(const Eigen::Vector2d& p1, const Eigen::Vector2d& c, int turn,
                 const Eigen::Vector2d& p2) {
  if (turn == 0) return 0.0;
  double alpha = std::atan2(p1.y() - c.y(), p1.x() - c.x());
  double beta = std::atan2(p2.y() - c.y(), p2.x() - c.x());
  if (turn > 0) {
    if (beta <= alpha) beta += 2.0 * kPi;
    return (beta - alpha) + (turn - 1) * (2.0 * kPi);
  }
  if (alpha <= beta) alpha += 2.0 * kPi;
  return (beta - alpha) + (turn + 1) * (2.0 * kPi);
}

// Compensation works in the plane's axes (first, second, normal): X Y Z in
// G17, Z X Y in G18 (rs274ngc's comp_get_current); the queue holds points so.
Eigen::Vector3d to_plane(const ExecState& st, const Eigen::Vector3d& p) {
  const std::array<int, 3> ax = plane_axes(st.plane);
  return {p[ax[0]], p[ax[1]], p[ax[2]]};
}
Eigen::Vector3d from_plane(const ExecState& st, const Eigen::Vector3d& q) {
  const std::array<int, 3> ax = plane_axes(st.plane);
  Eigen::Vector3d p;
  p[ax[0]] = q.x();
  p[ax[1]] = q.y();
  p[ax[2]] = q.z();
  return p;
}
Eigen::Vector2d xy(const Eigen::Vector3d& p) { return {p.x(), p.y()}; }
Eigen::Vector2d polar(double r, double angle) { return {r * std::cos(angle), r * std::sin(angle)}; }

const Word* anchor(const BlockPlan& b) {
  return b.motion_word
             ? b.motion_word
             : (b.codes.group(GGroup::cutter_comp) ? b.codes.group(GGroup::cutter_comp)->word
                                                   : nullptr);
}

[[noreturn]] void fail(const BlockPlan& b, const std::string& message) {
  b.ctx.fail(anchor(b), "cutter radius compensation: " + message);
}

void set_endpoint(CutterComp& c, const Eigen::Vector2d& p) {
  c.endpoint = p;
  c.endpoint_valid = true;
}

void enqueue(ExecState& st, const Eigen::Vector3d& start, CompEntry e) {
  CutterComp& c = st.comp;
  if (c.queue.empty()) c.queue_start = start;
  c.queue.push_back(std::move(e));
}

CompEntry straight_entry(const Motion& m, const Eigen::Vector3d& end, const Eigen::Vector2d& dir) {
  CompEntry e;
  e.m = m;
  e.m.rotation = 0;
  e.end = end;
  e.dir = dir;
  return e;
}

CompEntry arc_entry(const Motion& m, const Eigen::Vector3d& end, const Eigen::Vector2d& centre,
                    int turn, double original_turns) {
  CompEntry e;
  e.m = m;
  e.m.kind = MotionKind::arc;
  e.m.plane = Plane::xy;
  e.m.rotation = turn;
  e.end = end;
  e.centre = centre;
  e.original_turns = original_turns;
  return e;
}

// rs274ngc's dequeue_canons: the queue goes on as it is.
void dequeue(ExecState& st) {
  CutterComp& c = st.comp;
  c.endpoint_valid = false;
  if (c.queue.empty()) return;
  std::vector<CompEntry> queue;
  queue.swap(c.queue);
  Eigen::Vector3d from = c.queue_start;
  for (CompEntry& e : queue) {
    Motion& m = e.m;
    if (m.kind == MotionKind::dwell) {
      m.start = m.end = st.tip(from_plane(st, from));
    } else {
      m.start = st.tip(from_plane(st, from));
      m.end = st.tip(from_plane(st, e.end));
      if (m.kind == MotionKind::arc) {
        m.plane = st.plane;
        m.center = st.tip(from_plane(st, Eigen::Vector3d(e.centre.x(), e.centre.y(), from.z())));
      }
      from = e.end;
    }
    st.deliver(m);
  }
}

// rs274ngc's move_endpoint_and_flush: every queued move now ends at p (the
// corner found with the next move), then the queue goes on.
void move_endpoint_and_flush(ExecState& st, const BlockPlan& b, const Eigen::Vector2d& p) {
  CutterComp& c = st.comp;
  if (c.queue.empty()) return;
  for (CompEntry& e : c.queue) {
    if (e.m.kind == MotionKind::arc) {
      const double r1 = (xy(e.end) - e.centre).norm();
      const double r2 = (p - e.centre).norm();
      const double l2 = find_turn(c.endpoint, e.centre, e.m.rotation, p);
      if (std::abs(r1 - r2) > 0.01)
        fail(b,
             fmt::format("internal inconsistency: an arc end moved off its circle ({:g} to {:g})",
                         r1, r2));
      const double slack = st.inch ? 0.001 : 0.0254;
      if (e.original_turns != 0.0 && c.endpoint_valid &&
          std::abs(l2) > std::abs(e.original_turns) + slack)
        fail(b, "arc move in concave corner cannot be reached by the tool without gouging");
    } else if (e.m.kind != MotionKind::dwell) {
      const Eigen::Vector2d now = p - c.endpoint;
      if (c.endpoint_valid && e.dir.dot(now) < 0.0)
        fail(b, e.m.kind == MotionKind::rapid
                    ? "straight traverse in concave corner cannot be reached by the tool without "
                      "gouging"
                    : "straight feed in concave corner cannot be reached by the tool without "
                      "gouging");
    }
    if (e.m.kind != MotionKind::dwell) {
      e.end.x() = p.x();
      e.end.y() = p.y();
    }
  }
  dequeue(st);
  set_endpoint(c, p);
}

bool front_is_arc(const CutterComp& c) {
  return !c.queue.empty() && c.queue.front().m.kind == MotionKind::arc;
}

// The entry move (rs274ngc's convert_straight_comp1).
void straight_first(ExecState& st, const BlockPlan& b, const Eigen::Vector3d& p, const Motion& m) {
  CutterComp& c = st.comp;
  const Eigen::Vector3d from = to_plane(st, st.pos);
  const double distance = std::hypot(p.x() - from.x(), p.y() - from.y());
  if (distance <= c.radius)
    fail(b, fmt::format("the entry move ({:g}) is not longer than the tool radius ({:g})", distance,
                        c.radius));
  const double alpha =
      std::atan2(p.y() - from.y(), p.x() - from.x()) + (left(c) ? kHalfPi : -kHalfPi);
  const Eigen::Vector3d end(p.x() + c.radius * std::cos(alpha), p.y() + c.radius * std::sin(alpha),
                            p.z());
  set_endpoint(c, xy(from));
  enqueue(st, from, straight_entry(m, end, polar(1.0, alpha)));
  c.first_move = false;
  c.current = end;
}

// An arc as the entry move (rs274ngc's convert_arc_comp1): the end moves
// by the radius along the arc's normal there; the compensated arc from the
// current point to that end gets a new centre on the line from the end
// through the programmed centre.
void arc_first(ExecState& st, const BlockPlan& b, const Eigen::Vector3d& p,
               const Eigen::Vector2d& centre, const Motion& m) {
  CutterComp& c = st.comp;
  const int turn = m.rotation;
  const Eigen::Vector3d cur = to_plane(st, st.pos);
  const double radius = c.radius;
  if (std::hypot(p.x() - cur.x(), p.y() - cur.y()) <= radius)
    fail(b, "the radius of the entry arc is not greater than the tool radius");
  const bool inside = tool_inside_arc(c.side, turn);
  if (inside && (centre - xy(cur)).norm() <= radius)
    fail(b, fmt::format("the tool radius ({:g}) is not less than the arc radius ({:g})", radius,
                        (centre - xy(cur)).norm()));
  const double gamma = inside ? std::atan2(centre.y() - p.y(), centre.x() - p.x())
                              : std::atan2(p.y() - centre.y(), p.x() - centre.x());
  const Eigen::Vector3d end(p.x() + radius * std::cos(gamma), p.y() + radius * std::sin(gamma),
                            p.z());
  const double b_len = std::hypot(cur.y() - end.y(), cur.x() - end.x()) / 2.0;
  const double ab_ang = std::atan2(centre.y() - end.y(), centre.x() - end.x());
  const double a_ang = std::atan2(cur.y() - end.y(), cur.x() - end.x()) - ab_ang;
  if (std::abs(std::cos(a_ang)) < 0.0001)  // rs274ngc 2.9's TOLERANCE_EQUAL
    fail(b, "the tool radius is not less than the radius of the entry arc");
  const double c_len = b_len / std::cos(a_ang);
  const Eigen::Vector2d new_centre = xy(end) + polar(c_len, ab_ang);
  const ArcTolerances tol = arc_tolerances(st.inch);
  if (std::abs((new_centre - xy(end)).norm() - (new_centre - xy(cur)).norm()) > tol.spiral_abs)
    fail(b, "internal inconsistency in the entry arc");
  enqueue(st, cur,
          arc_entry(m, end, new_centre, turn, find_turn(xy(cur), new_centre, turn, xy(end))));
  c.first_move = false;
  c.current = end;
}

}  // namespace

void convert_cutter_comp(ExecState& st, const BlockPlan& b) {
  const auto& g = b.codes.group(GGroup::cutter_comp);
  if (!g) return;
  CutterComp& c = st.comp;
  if (g->code == gcode_id(40)) {
    // rs274ngc: the queued moves keep their ends; the program goes on from
    // the programmed point while the tool stands at the compensated one.
    if (c.offsetting() && !c.first_move) {
      move_endpoint_and_flush(st, b, xy(c.current));
      dequeue(st);
      c.exit_pending = true;
      c.exit_nose_mm = st.nose_mm(from_plane(st, c.current));
    }
    c.code = gcode_id(40);
    c.side = 0;
    c.radius = 0.0;
    c.first_move = true;
    return;
  }
  const Word* at = g->word;
  const bool dot_one = g->code == gcode_id(41, 1) || g->code == gcode_id(42, 1);
  const std::string name = gcode_name(g->code);
  if (st.plane == Plane::yz)
    b.ctx.fail(at, fmt::format("cutter radius compensation is allowed only in the XY or XZ "
                               "plane ({} in G19)",
                               name));
  if (c.side != 0)
    b.ctx.fail(at,
               fmt::format("cannot turn cutter radius compensation on when it is on ({})", name));
  const Word* d = b.codes.word('D');
  double radius = 0.0;
  if (dot_one) {
    if (!d) b.ctx.fail(at, fmt::format("{} with no D word (tool diameter)", name));
    if (const Word* l = b.codes.word('L'))
      b.ctx.fail(l, fmt::format("L word of {} (lathe tool orientation) is not supported", name));
    radius = d->value / 2.0;
  } else {
    int tool = st.tool_in_spindle;
    if (d) {
      if (std::abs(d->value - std::round(d->value)) >= 0.0001)
        b.ctx.fail(d, fmt::format("{} requires the D word to be a whole number", name));
      if (d->value < 0) b.ctx.fail(d, fmt::format("negative D word (tool number) with {}", name));
      if (d->value > 99999.0) b.ctx.fail(d, fmt::format("D word (tool number) above 99999"));
      tool = static_cast<int>(std::lround(d->value));
    } else if (tool == 0) {
      b.ctx.fail(at, fmt::format("cutter radius compensation ({}) without a D word and without a "
                                 "tool in the spindle (M6, M61): the cutter radius is unknown",
                                 name));
    }
    const auto it = st.config.tool_diameters.find(tool);
    if (it == st.config.tool_diameters.end())
      b.ctx.fail(d ? d : at, fmt::format("cutter radius compensation ({}{}): tool {} has no "
                                         "diameter in the tool table",
                                         name, d ? fmt::format(" D{}", tool) : "", tool));
    radius = it->second / st.unit() / 2.0;
  }
  if (st.config.dialect.dialect == Dialect::fanuc && !c.fanuc_warned) {
    c.fanuc_warned = true;
    spdlog::warn(
        "{}:{}: cutter radius compensation follows LinuxCNC's rules (entry move, arcs "
        "around outside corners); a Fanuc/Haas control may start up and go around "
        "outside corners differently (type A/B/C)",
        st.file, b.ctx.line);
  }
  int side = g->code == gcode_id(41) || g->code == gcode_id(41, 1) ? 1 : -1;
  if (radius < 0.0) {  // rs274ngc: a negative radius switches the side
    radius = -radius;
    side = -side;
  }
  c.code = g->code;
  c.side = side;
  c.radius = radius;
  c.first_move = true;
}

void check_comp_block(const ExecState& st, const BlockPlan& b) {
  const BlockCodes& c = b.codes;
  // rs274ngc: the move just after G40 must be a straight one (the tool is
  // not where the program continues from).
  if (st.comp.exit_pending && (b.motion == gcode_id(2) || b.motion == gcode_id(3)))
    b.ctx.fail(b.motion_word,
               "the move just after turning cutter radius compensation off (G40) "
               "must be straight");
  if (st.comp.side == 0) return;
  auto refuse = [&](const Word* w, const std::string& what) {
    b.ctx.fail(w, fmt::format("{} while cutter radius compensation is on is not supported", what));
  };
  // What rs274ngc executes before the cutter compensation step of a block
  // is refused even with G40 in it; what it executes after, only without.
  const auto& comp = c.group(GGroup::cutter_comp);
  const bool turning_off = comp && comp->code == gcode_id(40);
  if (const auto& g = c.group(GGroup::units)) refuse(g->word, gcode_name(g->code));
  if (const auto& g = c.group(GGroup::plane)) refuse(g->word, gcode_name(g->code));
  if (const auto& m = c.group(MGroup::tool_change)) refuse(m->word, fmt::format("M{}", m->code));
  if (const auto& m = c.group(MGroup::modal_save)) refuse(m->word, fmt::format("M{}", m->code));
  if (const auto& m = c.group(MGroup::overrides)) refuse(m->word, fmt::format("M{}", m->code));
  if (const auto& g = c.group(GGroup::feed_mode)) {
    if (g->code == gcode_id(93)) refuse(g->word, "inverse-time feed (G93)");
  } else if (st.feed_mode == FeedMode::inverse_time && b.motion >= 0 && !turning_off) {
    refuse(b.motion_word, "inverse-time feed (G93)");
  }
  if (turning_off) return;
  if (const auto& g = c.group(GGroup::tool_length)) refuse(g->word, gcode_name(g->code));
  if (const auto& g = c.group(GGroup::coord_system)) refuse(g->word, gcode_name(g->code));
  if (const auto& g = c.group(GGroup::path_control)) refuse(g->word, gcode_name(g->code));
  if (b.non_modal >= 0 && b.non_modal != gcode_id(4))
    refuse(c.group(GGroup::non_modal)->word, gcode_name(b.non_modal));
  if (b.motion >= 0 && is_cycle(b.motion)) refuse(b.motion_word, gcode_name(b.motion));
  if (c.has_polar_word()) refuse(c.has('@') ? c.word('@') : c.word('^'), "polar coordinates");
}

void comp_straight(ExecState& st, const BlockPlan& b, const Eigen::Vector3d& end_program,
                   const Motion& m) {
  CutterComp& c = st.comp;
  const bool rapid = m.kind == MotionKind::rapid;
  const Eigen::Vector3d p = to_plane(st, end_program);
  if (c.first_move) {
    straight_first(st, b, p, m);
    st.pos = end_program;
    return;
  }
  // rs274ngc's convert_straight_comp2.
  const Eigen::Vector3d cur = c.current;
  const Eigen::Vector3d op = to_plane(st, st.pos);  // the programmed start
  Eigen::Vector3d end = cur;
  end.z() = p.z();
  if (p.x() == op.x() && p.y() == op.y()) {  // no XY motion
    enqueue(st, cur, straight_entry(m, end, Eigen::Vector2d::Zero()));
  } else {
    const double radius = c.radius;
    double theta = std::atan2(cur.y() - op.y(), cur.x() - op.x());
    double alpha = std::atan2(p.y() - op.y(), p.x() - op.x());
    double beta = 0.0;
    double gamma = 0.0;
    if (left(c)) {
      if (theta < alpha) theta += 2.0 * kPi;
      beta = (theta - alpha) - kHalfPi;
      gamma = kHalfPi;
    } else {
      if (alpha < theta) alpha += 2.0 * kPi;
      beta = (alpha - theta) - kHalfPi;
      gamma = -kHalfPi;
    }
    end.x() = p.x() + radius * std::cos(alpha + gamma);
    end.y() = p.y() + radius * std::sin(alpha + gamma);
    Eigen::Vector2d mid(op.x() + radius * std::cos(alpha + gamma),
                        op.y() + radius * std::sin(alpha + gamma));
    bool concave = false;
    if (beta < -kSmall || beta > kPi + kSmall) {
      concave = true;
    } else if (beta > kPi - kSmall && front_is_arc(c)) {
      // An "h" shape: rs274ngc keeps the tool above and to the side.
      const int turn = c.queue.front().m.rotation;
      concave = (!left(c) && turn > 0) || (left(c) && turn < 0);
    }
    if (!concave && beta > kSmall) {  // outside corner: an arc about the programmed corner
      move_endpoint_and_flush(st, b, xy(cur));
      if (!rapid) {
        enqueue(st, cur,
                arc_entry(m, Eigen::Vector3d(mid.x(), mid.y(), cur.z()), xy(op), left(c) ? -1 : 1,
                          0.0));
      } else {  // no rapid arc: a rapid to the start of the offset line
        enqueue(
            st, cur,
            straight_entry(m, Eigen::Vector3d(mid.x(), mid.y(), cur.z()), Eigen::Vector2d::Zero()));
      }
      dequeue(st);
      set_endpoint(c, mid);
      CompEntry line = straight_entry(m, end, Eigen::Vector2d(p.x() - op.x(), p.y() - op.y()));
      ++line.m.sub;  // the corner is the block's first motion, the line its second
      enqueue(st, Eigen::Vector3d(mid.x(), mid.y(), cur.z()), std::move(line));
    } else {
      if (concave) {
        if (!front_is_arc(c)) {  // line -> line
          const double halfcorner = (beta + kPi) / 2.0;
          if (halfcorner == 0.0) fail(b, "zero degree inside corner is invalid");
          const double retreat = radius / std::tan(halfcorner);
          mid = xy(cur) + polar(retreat, theta + gamma);
          move_endpoint_and_flush(st, b, mid);
        } else {  // arc -> line
          const CompEntry& prev = c.queue.front();
          const int turn = prev.m.rotation;
          const double oldrad = (xy(prev.end) - prev.centre).norm();
          const double base_dir = std::atan2(p.y() - op.y(), p.x() - op.x());
          const double th = turn > 0 ? base_dir + kHalfPi : base_dir - kHalfPi;
          const double phi = std::atan2(prev.centre.y() - op.y(), prev.centre.x() - op.x());
          const bool inside = tool_inside_arc(c.side, turn);
          const double oldrad_uncomp = inside ? oldrad + radius : oldrad - radius;
          const double d = oldrad_uncomp * std::cos(th - phi);
          const double l = (inside ? d - radius : d + radius) / oldrad;
          if (l > 1.0 || l < -1.0)
            fail(b,
                 "arc to straight motion makes a corner the compensated tool can't fit in "
                 "without gouging");
          double angle;
          if (inside)
            angle = turn > 0 ? -std::acos(l) + th + kPi : std::acos(l) + th + kPi;
          else
            angle = turn > 0 ? std::acos(l) + th + kPi : -std::acos(l) + th + kPi;
          mid = prev.centre + polar(oldrad, angle);
          move_endpoint_and_flush(st, b, mid);
        }
      } else {  // no corner (in line, or tangent)
        dequeue(st);
        set_endpoint(c, xy(cur));
      }
      enqueue(st, Eigen::Vector3d(c.endpoint.x(), c.endpoint.y(), cur.z()),
              straight_entry(m, end, Eigen::Vector2d(p.x() - op.x(), p.y() - op.y())));
    }
  }
  c.current = end;
  st.pos = end_program;
}

void comp_arc(ExecState& st, const BlockPlan& b, const Eigen::Vector3d& end_program,
              const Eigen::Vector2d& centre, const Motion& m) {
  CutterComp& c = st.comp;
  const Eigen::Vector3d p = to_plane(st, end_program);
  if (c.first_move) {
    arc_first(st, b, p, centre, m);
    st.pos = end_program;
    return;
  }
  // rs274ngc's convert_arc_comp2.
  const int turn = m.rotation;
  const bool g3 = turn > 0;
  const double radius = c.radius;
  const Eigen::Vector3d cur = c.current;
  const Eigen::Vector3d op = to_plane(st, st.pos);
  const double arc_radius = (centre - xy(p)).norm();
  double theta = std::atan2(cur.y() - op.y(), cur.x() - op.x());
  theta = left(c) ? theta - kHalfPi : theta + kHalfPi;
  double delta = std::atan2(centre.y() - op.y(), centre.x() - op.x());
  const double alpha = g3 ? delta - kHalfPi : delta + kHalfPi;
  double beta = left(c) ? theta - alpha : alpha - theta;
  beta = beta > 1.5 * kPi ? beta - 2.0 * kPi : beta < -kHalfPi ? beta + 2.0 * kPi : beta;
  double gamma;
  if ((left(c) && g3) || (!left(c) && !g3)) {
    gamma = std::atan2(centre.y() - p.y(), centre.x() - p.x());
    if (arc_radius <= radius)
      fail(b, fmt::format("the tool radius ({:g}) is not less than the arc radius ({:g})", radius,
                          arc_radius));
  } else {
    gamma = std::atan2(p.y() - centre.y(), p.x() - centre.x());
    delta += kPi;
  }
  const Eigen::Vector3d new_end(p.x() + radius * std::cos(gamma), p.y() + radius * std::sin(gamma),
                                p.z());
  const double sweep = find_turn(xy(op), centre, turn, xy(p));
  const bool inside = tool_inside_arc(c.side, turn);
  if (beta < -kSmall || beta > kPi + kSmall || (std::abs(beta - kPi) < kSmall && !inside)) {
    Eigen::Vector2d mid;
    if (!front_is_arc(c)) {  // line -> arc, inside corner
      const double cy = arc_radius * std::sin(beta - kHalfPi);
      double angle;
      if (inside) {
        const double dist = arc_radius - radius;
        const double l = (cy + radius) / dist;
        if (l > 1.0 || l < -1.0)
          fail(b, "arc move in concave corner cannot be reached by the tool without gouging");
        angle = turn > 0 ? theta + std::asin(l) : theta - std::asin(l);
        mid = centre + polar(dist, angle);
      } else {
        const double dist = arc_radius + radius;
        const double l = (cy - radius) / dist;
        if (l > 1.0 || l < -1.0)
          fail(b, "arc move in concave corner cannot be reached by the tool without gouging");
        angle = turn > 0 ? theta + kPi - std::asin(l) : theta + kPi + std::asin(l);
        mid = centre + polar(dist, angle);
      }
    } else {  // arc -> arc, inside corner
      const CompEntry& prev = c.queue.front();
      const double oldrad = (xy(prev.end) - prev.centre).norm();
      const double newrad = inside ? arc_radius - radius : arc_radius + radius;
      const double arc_cc = (prev.centre - centre).norm();
      if (oldrad == 0.0 || arc_cc == 0.0)
        fail(b, "arc to arc motion is invalid because the arcs have the same center");
      const double a =
          (oldrad * oldrad + arc_cc * arc_cc - newrad * newrad) / (2 * oldrad * arc_cc);
      if (a > 1.0 || a < -1.0)
        fail(b,
             "arc to arc motion makes a corner the compensated tool can't fit in without "
             "gouging");
      const double pullback = std::acos(a);
      const double cc_dir = std::atan2(centre.y() - prev.centre.y(), centre.x() - prev.centre.x());
      double dir;
      if (tool_inside_arc(c.side, prev.m.rotation))
        dir = turn > 0 ? cc_dir + pullback : cc_dir - pullback;
      else
        dir = turn > 0 ? cc_dir - pullback : cc_dir + pullback;
      mid = prev.centre + polar(oldrad, dir);
    }
    move_endpoint_and_flush(st, b, mid);
    enqueue(st, Eigen::Vector3d(mid.x(), mid.y(), cur.z()),
            arc_entry(m, new_end, centre, turn, sweep));
  } else if (beta > kSmall) {  // outside corner: an arc about the programmed corner, then the arc
    const Eigen::Vector2d mid = xy(op) + polar(radius, delta);
    dequeue(st);
    enqueue(
        st, cur,
        arc_entry(m, Eigen::Vector3d(mid.x(), mid.y(), cur.z()), xy(op), left(c) ? -1 : 1, 0.0));
    dequeue(st);
    set_endpoint(c, mid);
    CompEntry arc = arc_entry(m, new_end, centre, turn, sweep);
    ++arc.m.sub;  // the corner is the block's first motion, the arc its second
    enqueue(st, Eigen::Vector3d(mid.x(), mid.y(), cur.z()), std::move(arc));
  } else {  // tangent
    dequeue(st);
    set_endpoint(c, xy(cur));
    enqueue(st, cur, arc_entry(m, new_end, centre, turn, sweep));
  }
  c.current = new_end;
  st.pos = end_program;
}

void comp_flush(ExecState& st) { dequeue(st); }

void comp_enqueue_dwell(ExecState& st, const Motion& m) {
  CompEntry e;
  e.m = m;
  st.comp.queue.push_back(std::move(e));
}

}  // namespace abbe::gcode::detail
