#include "abbe/compensate/path_verifier.hpp"

#include <cmath>
#include <deque>
#include <functional>

#include "abbe/compensate/motion_path.hpp"
#include "abbe/gcode/parser.hpp"
#include "abbe/path/fragmenter.hpp"

namespace abbe::compensate {
namespace {

using Eigen::Vector3d;

// Pulls the motions of a program one at a time.
class MotionStream {
 public:
  MotionStream(std::istream& in, const std::string& file, const gcode::InterpreterConfig& config)
      : reader_(in, file), interp_(config, file) {}
  bool next(gcode::Motion& m) {
    while (pending_.empty()) {
      if (interp_.program_ended() || !reader_.next(block_)) return false;
      interp_.execute(block_, reader_.raw_line(),
                      [&](const gcode::Motion& x) { pending_.push_back(x); });
    }
    m = pending_.front();
    pending_.pop_front();
    return true;
  }

 private:
  gcode::BlockReader reader_;
  gcode::Interpreter interp_;
  gcode::Block block_;
  std::deque<gcode::Motion> pending_;
};

bool is_feed(const gcode::Motion& m) {
  return m.kind == gcode::MotionKind::linear || m.kind == gcode::MotionKind::arc;
}

// Direction signs of the compensated path for the table lookups: an axis
// counts as moving in a motion only if it moves by more than `deadband`
// over it; smaller moves are compensation corrections of an axis that is
// nominally at rest and keep its previous direction (as the solver, which
// uses the nominal directions). Within arcs the in-plane axes follow the
// tangent.
class DirectionTracker {
 public:
  explicit DirectionTracker(double deadband) : deadband_(deadband) {}
  std::array<std::int8_t, 3> update(const gcode::Motion& m) {
    for (int k = 0; k < 3; ++k) {
      const double d = m.end[k] - m.start[k];
      if (std::abs(d) > deadband_) dir_[static_cast<std::size_t>(k)] = d > 0 ? 1 : -1;
    }
    return dir_;
  }

 private:
  double deadband_;
  std::array<std::int8_t, 3> dir_{0, 0, 0};
};

struct Curve {
  gcode::Motion motion;
  MotionPath path;
  std::array<std::int8_t, 3> dir;  // at the end of the motion
};

struct PassStats {
  std::size_t n = 0;
  double max = 0.0, sum2 = 0.0;
  std::size_t max_line = 0;
};

// Streams the feed points of `a` (mapped by `point`) and measures each to the
// nearest of a window of `b`'s feed curves (distance by `dist`).
PassStats run_pass(MotionStream& a, MotionStream& b, double step, std::size_t window,
                   double deadband, const std::function<Vector3d(const path::PathPoint&)>& point,
                   const std::function<double(const Curve&, const Vector3d&)>& dist) {
  PassStats st;
  path::Fragmenter fa(path::FragmentOptions{step, 10000.0});
  path::Fragmenter fb(path::FragmentOptions{step, 10000.0});
  std::deque<Curve> curves;
  std::size_t cursor = 0;
  bool b_done = false;
  DirectionTracker ta(deadband), tb(deadband);
  auto pull = [&]() {
    gcode::Motion m;
    while (!b_done) {
      if (!b.next(m)) {
        b_done = true;
        return;
      }
      const std::array<std::int8_t, 3> dir = tb.update(m);
      bool any = false;
      fb.add(m, [&](const path::PathPoint&) { any = true; });
      if (is_feed(m) && any) {
        curves.push_back({m, MotionPath(m), dir});
        return;
      }
    }
  };
  gcode::Motion m;
  while (a.next(m)) {
    const bool feed = is_feed(m);
    const std::array<std::int8_t, 3> base = ta.update(m);
    const auto plane = plane_axes(m.plane);
    fa.add(m, [&](const path::PathPoint& fp) {
      if (!feed || (fp.p - m.start).norm() == 0.0) return;
      path::PathPoint pp = fp;
      for (std::size_t k = 0; k < 3; ++k)
        if (m.kind != gcode::MotionKind::arc || static_cast<int>(k) == plane[2])
          pp.dir[k] = base[k];
      while (!b_done && curves.size() < cursor + window + 1) pull();
      if (curves.empty()) return;
      const Vector3d q = point(pp);
      const std::size_t lo = cursor > 0 ? cursor - 1 : 0;
      const std::size_t hi = std::min(curves.size(), cursor + window + 1);
      double best = std::numeric_limits<double>::infinity();
      std::size_t arg = cursor;
      for (std::size_t i = lo; i < hi; ++i) {
        const double d = dist(curves[i], q);
        if (d < best - 1e-12) {
          best = d;
          arg = i;
        }
      }
      if (arg > cursor) cursor = arg;
      while (cursor > 1) {
        curves.pop_front();
        --cursor;
      }
      const double um = 1e3 * best;
      ++st.n;
      st.sum2 += um * um;
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
  // Forward: predicted compensated points to the nominal original curves.
  {
    MotionStream a(compensated, compensated_file, config);
    MotionStream b(original, original_file, config);
    const PassStats st = run_pass(
        a, b, options.step, options.window, options.deadband,
        [&](const path::PathPoint& pp) {
          return Vector3d(pp.p + error_mm(pp.p, pp.tool_length, pp.dir));
        },
        [](const Curve& c, const Vector3d& q) { return c.path.distance(q); });
    out.points = st.n;
    out.max_um = st.max;
    out.rms_um = st.n ? std::sqrt(st.sum2 / static_cast<double>(st.n)) : 0.0;
    out.max_line = st.max_line;
  }
  // Backward: nominal original points to the predicted compensated curves.
  compensated.clear();
  compensated.seekg(0);
  original.clear();
  original.seekg(0);
  {
    MotionStream a(original, original_file, config);
    MotionStream b(compensated, compensated_file, config);
    const PassStats st = run_pass(
        a, b, options.step, options.window, options.deadband,
        [](const path::PathPoint& pp) { return pp.p; },
        [&](const Curve& c, const Vector3d& q) {
          // The point of the predicted curve nearest to q: the commanded
          // point p whose prediction p + e(p) is nearest, by iterating
          // t ← closest(q − e(p(t))); directions as in the forward pass,
          // the in-plane axes of an arc from its tangent.
          Vector3d e = Vector3d::Zero();
          Vector3d p = Vector3d::Zero();
          for (int it = 0; it < 3; ++it) {
            const double t = c.path.closest(q - e);
            p = c.path.at(t);
            std::array<std::int8_t, 3> dir = c.dir;
            if (c.path.is_arc()) {
              const double h = 1e-4;
              const Vector3d v = c.path.at(std::min(1.0, t + h)) - c.path.at(std::max(0.0, t - h));
              const auto plane = plane_axes(c.motion.plane);
              for (int k = 0; k < 2; ++k) {
                const int i = plane[static_cast<std::size_t>(k)];
                if (std::abs(v[i]) > 1e-9) dir[static_cast<std::size_t>(i)] = v[i] > 0 ? 1 : -1;
              }
            }
            e = error_mm(p, c.motion.tool_length, dir);
          }
          return (p + e - q).norm();
        });
    out.backward_points = st.n;
    out.backward_max_um = st.max;
    out.backward_rms_um = st.n ? std::sqrt(st.sum2 / static_cast<double>(st.n)) : 0.0;
    out.backward_max_line = st.max_line;
  }
  out.out_of_range_lookups = data.out_of_range_lookups;
  return out;
}

}  // namespace abbe::compensate
