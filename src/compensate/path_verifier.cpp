#include "abbe/compensate/path_verifier.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <deque>
#include <functional>
#include <limits>
#include <optional>
#include <vector>

#include "abbe/compensate/motion_path.hpp"
#include "abbe/gcode/parser.hpp"
#include "abbe/path/fragmenter.hpp"

namespace abbe::compensate {
namespace {

using Eigen::Vector3d;

// Pulls the motions of a program one at a time. In a canned cycle (a block
// with several motions) only the hole bottoms are compared — compensate
// corrects the hole position there, the cycle words stay — so the other
// motions of the block are flagged.
class MotionStream {
 public:
  MotionStream(std::istream& in, const std::string& file, const gcode::InterpreterConfig& config)
      : reader_(in, file), interp_(config, file) {}
  // `bottom_only`: measure only the end point (a hole bottom), or nothing.
  bool next(gcode::Motion& m, bool& skip) {
    while (pending_.empty()) {
      if (interp_.program_ended() || !reader_.next(block_)) return false;
      block_motions_.clear();
      interp_.execute(block_, reader_.raw_line(), [&](const gcode::Motion& x) {
        if (x.kind != gcode::MotionKind::dwell) block_motions_.push_back(x);
      });
      const bool cycle = block_motions_.size() > 1;
      for (std::size_t i = 0; i < block_motions_.size(); ++i) {
        const gcode::Motion& x = block_motions_[i];
        bool bottom = false;
        if (cycle && x.kind == gcode::MotionKind::linear) {
          const Eigen::Vector3d d = x.end - x.start;
          bottom = i + 1 < block_motions_.size() &&
                   (block_motions_[i + 1].end - block_motions_[i + 1].start).dot(d) < 0.0;
        }
        pending_.push_back({x, cycle && !bottom});
      }
    }
    m = pending_.front().first;
    skip = pending_.front().second;
    pending_.pop_front();
    return true;
  }

 private:
  gcode::BlockReader reader_;
  gcode::Interpreter interp_;
  gcode::Block block_;
  std::vector<gcode::Motion> block_motions_;
  std::deque<std::pair<gcode::Motion, bool>> pending_;
};

bool is_feed(const gcode::Motion& m) {
  return m.kind == gcode::MotionKind::linear || m.kind == gcode::MotionKind::arc;
}

struct Curve {
  gcode::Motion motion;
  MotionPath path;
  std::array<std::int8_t, 3> dir;  // at the end of the motion (its own program's directions)
  Eigen::AlignedBox3d box;         // bounds the curve
};

Eigen::AlignedBox3d bounds(const gcode::Motion& m) {
  Eigen::AlignedBox3d b(m.start);
  b.extend(m.end);
  if (m.kind == gcode::MotionKind::arc) {
    const double r = std::max((m.start - m.center).norm(), (m.end - m.center).norm());
    b.extend(m.center - Eigen::Vector3d::Constant(r));
    b.extend(m.center + Eigen::Vector3d::Constant(r));
  }
  return b;
}

// Direction signs on a curve at parameter t: the curve's own; for the
// in-plane axes of an arc, the chord from one fragment step back (what the
// fragmenter gives the solver: the sign of the last motion before the point).
std::array<std::int8_t, 3> direction_at(const Curve& c, double t, double step) {
  std::array<std::int8_t, 3> dir = c.dir;
  if (c.path.is_arc()) {
    const double h = c.path.length() > 0.0 ? std::min(0.5, 0.02 * step / c.path.length()) : 1e-4;
    const Vector3d v = c.path.at(t) - c.path.at(std::max(0.0, t - h));
    const auto plane = plane_axes(c.motion.plane);
    for (int k = 0; k < 2; ++k) {
      const int i = plane[static_cast<std::size_t>(k)];
      if (std::abs(v[i]) > 1e-9) dir[static_cast<std::size_t>(i)] = v[i] > 0 ? 1 : -1;
    }
  }
  return dir;
}

struct PassStats {
  std::size_t n = 0;
  double max = 0.0, sum2 = 0.0;
  std::size_t max_line = 0;
  std::size_t over = 0;
};

using CurveMetric = std::function<double(const Curve&, const path::PathPoint&)>;

// Streams the feed points of `a`; each is matched to the nearest (by
// `match`) of a window of `b`'s feed curves and measured (by `measure`).
PassStats run_pass(MotionStream& a, MotionStream& b, double step, std::size_t window, double slack,
                   double tol_um, const CurveMetric& match, const CurveMetric& measure) {
  PassStats st;
  path::Fragmenter fa(path::FragmentOptions{step, 10000.0});
  path::Fragmenter fb(path::FragmentOptions{step, 10000.0});
  std::deque<Curve> curves;
  std::size_t cursor = 0;
  bool b_done = false;
  auto pull = [&]() {
    gcode::Motion m;
    bool skip_b = false;
    while (!b_done) {
      if (!b.next(m, skip_b)) {
        b_done = true;
        return;
      }
      std::array<std::int8_t, 3> dir{0, 0, 0};
      bool any = false;
      fb.add(m, [&](const path::PathPoint& pp) {
        dir = pp.dir;
        any = true;
      });
      if (is_feed(m) && any) {
        curves.push_back({m, MotionPath(m), dir, bounds(m)});
        return;
      }
    }
  };
  gcode::Motion m;
  bool skip = false;
  while (a.next(m, skip)) {
    const bool feed = is_feed(m) && !skip;
    const bool cycle = m.sub > 0 || skip;
    fa.add(m, [&](const path::PathPoint& pp) {
      if (!feed || (pp.p - m.start).norm() == 0.0) return;
      if (cycle && pp.p != m.end) return;  // a hole: its bottom only
      while (!b_done && curves.size() < cursor + window + 1) pull();
      if (curves.empty()) return;
      // Candidates: the curves within `slack` of the best match (a point at
      // a corner or where the path passes itself is near several). The
      // cursor moves to the first of them in path order from the current
      // curve; the point is measured to the nearest of them.
      const std::size_t lo = cursor > 0 ? cursor - 1 : 0;
      const std::size_t hi = std::min(curves.size(), cursor + window + 1);
      std::vector<double> d(hi - lo);
      double best = std::numeric_limits<double>::infinity();
      // The box distance bounds the match from below (less the largest
      // correction, 0.5 mm, for the predicted metric): far curves are skipped.
      for (std::size_t i = lo; i < hi; ++i) {
        const double lb = curves[i].box.exteriorDistance(pp.p) - 0.5;
        d[i - lo] =
            lb > best + slack ? std::numeric_limits<double>::infinity() : match(curves[i], pp);
        best = std::min(best, d[i - lo]);
      }
      std::optional<std::size_t> next;
      double um = std::numeric_limits<double>::infinity();
      for (std::size_t i = lo; i < hi; ++i) {
        if (d[i - lo] > best + slack) continue;
        if (i >= cursor && !next) next = i;
        um = std::min(um, 1e3 * measure(curves[i], pp));
      }
      if (next && *next > cursor) cursor = *next;
      while (cursor > 1) {
        curves.pop_front();
        --cursor;
      }
      ++st.n;
      st.sum2 += um * um;
      if (um > tol_um) ++st.over;
      if (um > st.max) {
        st.max = um;
        st.max_line = pp.line;
      }
    });
  }
  return st;
}

}  // namespace

VerifyStats verify_program(std::istream& compensated, const std::string& compensated_file,
                           std::istream& original, const std::string& original_file,
                           const gcode::InterpreterConfig& config, const model::ErrorModel& model,
                           const VerifyOptions& options) {
  VerifyStats out;
  model::ModelData data;
  auto error_mm = [&](const Vector3d& p, double l, const std::array<std::int8_t, 3>& dir) {
    model::EvalPoint ep;
    ep.p = p;
    ep.tool_length = l;
    ep.dir = dir;
    return Vector3d(1e-3 * model.evaluate(ep, data).e_um);
  };
  // Forward: each commanded point c of the compensated program is matched to
  // the nearest nominal curve, predicted with that curve's (nominal)
  // direction signs — those the solver used — and measured to the curve.
  {
    MotionStream a(compensated, compensated_file, config);
    MotionStream b(original, original_file, config);
    const PassStats st = run_pass(
        a, b, options.step, options.window, options.slack, options.tol_um,
        [](const Curve& c, const path::PathPoint& pp) { return c.path.distance(pp.p); },
        [&](const Curve& c, const path::PathPoint& pp) {
          const auto dir = direction_at(c, c.path.closest(pp.p), options.step);
          return c.path.distance(pp.p + error_mm(pp.p, pp.tool_length, dir));
        });
    out.points = st.n;
    out.max_um = st.max;
    out.rms_um = st.n ? std::sqrt(st.sum2 / static_cast<double>(st.n)) : 0.0;
    out.max_line = st.max_line;
    out.over_tol = st.over;
  }
  compensated.clear();
  compensated.seekg(0);
  original.clear();
  original.seekg(0);
  // Backward: each nominal point n of the original to the predicted
  // compensated curve: the commanded point p whose prediction p + e(p) is
  // nearest to n, by iterating t ← closest(n − e(p(t))), with n's directions.
  {
    MotionStream a(original, original_file, config);
    MotionStream b(compensated, compensated_file, config);
    const CurveMetric predicted = [&](const Curve& c, const path::PathPoint& pp) {
      Vector3d e = Vector3d::Zero();
      Vector3d p = Vector3d::Zero();
      for (int it = 0; it < 3; ++it) {
        p = c.path.at(c.path.closest(pp.p - e));
        e = error_mm(p, c.motion.tool_length, pp.dir);
      }
      return (p + e - pp.p).norm();
    };
    const PassStats st = run_pass(a, b, options.step, options.window, options.slack, options.tol_um,
                                  predicted, predicted);
    out.backward_points = st.n;
    out.backward_max_um = st.max;
    out.backward_rms_um = st.n ? std::sqrt(st.sum2 / static_cast<double>(st.n)) : 0.0;
    out.backward_max_line = st.max_line;
    out.backward_over_tol = st.over;
  }
  out.out_of_range_lookups = data.out_of_range_lookups;
  return out;
}

}  // namespace abbe::compensate
