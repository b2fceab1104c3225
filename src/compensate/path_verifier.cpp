#include "abbe/compensate/path_verifier.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <optional>
#include <vector>

#include "abbe/compensate/motion_path.hpp"
#include "abbe/gcode/motion_limits.hpp"
#include "abbe/gcode/parser.hpp"
#include "abbe/io/input_error.hpp"
#include "abbe/path/fragmenter.hpp"

namespace abbe::compensate {
namespace {

using Eigen::Vector3d;
using Dir = std::array<std::int8_t, 3>;

// Pulls the motions of a program one at a time. In a canned cycle (a block
// with several motions) only the hole bottoms are compared — compensate
// corrects the hole position there, the cycle words stay — so the other
// motions of the block are flagged.
class MotionStream {
 public:
  MotionStream(std::istream& in, const std::string& file, const gcode::InterpreterConfig& config)
      : reader_(in, file),
        interp_(config, file),
        fanuc_(config.dialect.dialect == gcode::Dialect::fanuc) {}
  const std::string& file() const { return reader_.file(); }
  // `skip`: a motion of a canned cycle that is not a hole bottom.
  bool next(gcode::Motion& m, bool& skip) {
    while (head_ == skip_.size()) {
      if (interp_.program_ended() || !reader_.next(block_)) return false;
      if (fanuc_)
        if (const gcode::Word* w = gcode::subprogram_flow_word(block_))
          throw InputError({reader_.file(), block_.line, static_cast<std::size_t>(w->begin) + 1, "",
                            reader_.raw_line()},
                           "subprogram calls (M98/M99) are not followed by verify, as compensate "
                           "does not compensate them");
      block_motions_.clear();
      head_ = 0;
      interp_.execute(block_, reader_.line_text(), [&](const gcode::Motion& x) {
        if (x.kind != gcode::MotionKind::dwell) block_motions_.push_back(x);
      });
      // A hole: the motions at one position of the plane; its bottom is the
      // feed end deepest along the drill axis (pecks stop short of it).
      const bool cycle = block_motions_.size() > 1;
      skip_.assign(block_motions_.size(), cycle);
      if (cycle) {
        const auto ax = plane_axes(interp_.plane());
        const auto same_place = [&](const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
          return p[ax[0]] == q[ax[0]] && p[ax[1]] == q[ax[1]];
        };
        for (std::size_t i = 0; i < block_motions_.size();) {
          std::size_t j = i;
          while (j < block_motions_.size() &&
                 same_place(block_motions_[j].end, block_motions_[i].end))
            ++j;
          const double top = block_motions_[i].start[ax[2]];
          std::optional<std::size_t> bottom;
          for (std::size_t k = i; k < j; ++k) {
            if (block_motions_[k].kind != gcode::MotionKind::linear) continue;
            if (!bottom || std::abs(block_motions_[k].end[ax[2]] - top) >
                               std::abs(block_motions_[*bottom].end[ax[2]] - top))
              bottom = k;
          }
          if (bottom) skip_[*bottom] = false;
          i = j;
        }
      }
    }
    m = block_motions_[head_];
    skip = skip_[head_];
    ++head_;
    return true;
  }

 private:
  gcode::BlockReader reader_;
  gcode::Interpreter interp_;
  bool fanuc_ = false;
  gcode::Block block_;
  std::vector<gcode::Motion> block_motions_;
  std::vector<bool> skip_;  // per motion of the block: `skip` of next()
  std::size_t head_ = 0;
};

// Runs `f`, which fragments motion `m` of stream `s`; a motion the
// fragmenter refuses is bad input at its line.
template <class F>
void refusing(const MotionStream& s, const gcode::Motion& m, const F& f) {
  try {
    f();
  } catch (const gcode::MotionRefused& e) {
    throw InputError({s.file(), m.line, 0, "", ""}, e.what());
  }
}

bool is_feed(const gcode::Motion& m) {
  return m.kind == gcode::MotionKind::linear || m.kind == gcode::MotionKind::arc;
}

struct Curve {
  gcode::Motion motion;
  MotionPath path;
  Dir dir;                  // at the end of the motion (its own program's directions)
  Eigen::AlignedBox3d box;  // bounds the curve
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

struct PassStats {
  std::size_t n = 0;
  double max = 0.0, sum2 = 0.0;
  std::size_t max_line = 0;
  std::size_t over = 0;
  std::size_t unmatched = 0;
  // Into one direction's fields of VerifyStats (the RMS over matched points).
  void store(std::size_t& points, double& max_um, double& rms_um, std::size_t& line,
             std::size_t& over_tol, std::size_t& unmatched_points) const {
    points = n;
    max_um = max;
    rms_um = n > unmatched ? std::sqrt(sum2 / static_cast<double>(n - unmatched)) : 0.0;
    line = max_line;
    over_tol = over;
    unmatched_points = unmatched;
  }
};

// Streams the feed points of `a`; each is matched to the nearest (by
// `match`) of a window of `b`'s feed curves and measured (by `measure`).
// `arc_dirs`: the points of `a`'s arcs get the in-plane directions of the
// shared convention (MotionPath::near_lo): a reversal within kNearReversal of
// an end counts as at that end.
template <class Match, class Measure>
PassStats run_pass(MotionStream& a, MotionStream& b, double step, std::size_t window, double slack,
                   double tol_um, bool arc_dirs, const Match& match, const Measure& measure) {
  PassStats st;
  path::Fragmenter fa(path::FragmentOptions{step, 10000.0});
  path::Fragmenter fb(path::FragmentOptions{step, 10000.0});
  std::deque<Curve> curves;
  std::vector<double> d;
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
      Dir dir{0, 0, 0};
      bool any = false;
      refusing(b, m, [&] {
        fb.add(m, [&](const path::PathPoint& pp) {
          dir = pp.dir;
          any = true;
        });
      });
      if (is_feed(m) && any && !skip_b) {
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
    std::optional<MotionPath> arc;
    if (arc_dirs && feed && m.kind == gcode::MotionKind::arc) arc.emplace(m);
    refusing(a, m, [&] {
      fa.add(m, [&](const path::PathPoint& point) {
        if (!feed || (point.p - m.start).norm() == 0.0) return;
        if (cycle && point.p != m.end) return;  // a hole: its bottom only
        path::PathPoint pp = point;
        if (arc)
          pp.dir =
              arc->directions(pp.dir, std::clamp(arc->closest(pp.p), arc->near_lo(kNearReversal),
                                                 arc->near_hi(kNearReversal)));
        while (!b_done && curves.size() < cursor + window + 1) pull();
        if (curves.empty()) {  // nothing to match: a failure, not a pass
          ++st.n;
          ++st.unmatched;
          ++st.over;
          if (st.max < std::numeric_limits<double>::infinity()) {
            st.max = std::numeric_limits<double>::infinity();
            st.max_line = pp.line;
          }
          return;
        }
        // Candidates: the curves within `slack` of the best match (a point at
        // a corner or where the path passes itself is near several). The
        // cursor moves to the first of them in path order from the current
        // curve; the point is measured to the nearest of them.
        const std::size_t lo = cursor > 0 ? cursor - 1 : 0;
        const std::size_t hi = std::min(curves.size(), cursor + window + 1);
        d.assign(hi - lo, std::numeric_limits<double>::infinity());
        double best = std::numeric_limits<double>::infinity();
        // The box distance bounds the match from below (less the largest
        // correction, 0.5 mm, for the predicted metric): far curves are skipped.
        for (std::size_t i = lo; i < hi; ++i) {
          const double lb = curves[i].box.exteriorDistance(pp.p) - 0.5;
          if (lb > best + slack) continue;
          d[i - lo] = match(curves[i], pp);
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
  auto error_mm = [&](const Vector3d& p, double l, const Dir& dir) {
    model::EvalPoint ep;
    ep.p = p;
    ep.tool_length = l;
    ep.dir = dir;
    return Vector3d(1e-3 * model.evaluate(ep, data).e_um);
  };
  // Forward: each commanded point c of the compensated program is predicted
  // with the direction signs of the nominal curve where it belongs — those
  // the solver used — and measured to that curve: the least over t of
  // |c + e(c, D(t)) − n(t)|, D(t) the nominal directions at t. D changes
  // only at the reversal points of an arc; near one (within the largest
  // correction) both sides are measured, each on its own side: a point at
  // the reversal belongs to the side whose tables it was solved with.
  {
    MotionStream a(compensated, compensated_file, config);
    MotionStream b(original, original_file, config);
    const auto match = [](const Curve& c, const path::PathPoint& pp) {
      return c.path.distance(pp.p);
    };
    const auto measure = [&](const Curve& c, const path::PathPoint& pp) {
      if (!c.path.is_arc()) return c.path.distance(pp.p + error_mm(pp.p, pp.tool_length, c.dir));
      const double t0 = c.path.closest(pp.p);
      const double w = c.path.length() > 0.0 ? 0.5 / c.path.length() : 1.0;
      const double t_lo = std::max(0.0, t0 - w), t_hi = std::min(1.0, t0 + w);
      const double lo = c.path.near_lo(kNearReversal), hi = c.path.near_hi(kNearReversal);
      double bounds_t[8];
      int nb = 0;
      bounds_t[nb++] = t_lo;
      c.path.for_each_reversal(std::max(t_lo, lo), std::min(t_hi, hi), [&](double t) {
        if (nb < 7) bounds_t[nb++] = t;
      });
      bounds_t[nb++] = t_hi;
      double best = std::numeric_limits<double>::infinity();
      for (int s = 0; s + 1 < nb; ++s) {
        const double sa = bounds_t[s], sb = bounds_t[s + 1];
        const double mid = std::clamp(0.5 * (sa + sb), lo, hi);
        const Vector3d q = pp.p + error_mm(pp.p, pp.tool_length, c.path.directions(c.dir, mid));
        const double t = std::clamp(c.path.closest(q), sa, sb);
        best = std::min(best, (c.path.at(t) - q).norm());
      }
      return best;
    };
    const PassStats st = run_pass(a, b, options.step, options.window, options.slack, options.tol_um,
                                  false, match, measure);
    st.store(out.points, out.max_um, out.rms_um, out.max_line, out.over_tol, out.unmatched);
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
    const auto predicted = [&](const Curve& c, const path::PathPoint& pp) {
      Vector3d e = Vector3d::Zero();
      Vector3d p = Vector3d::Zero();
      for (int it = 0; it < 3; ++it) {
        p = c.path.at(c.path.closest(pp.p - e));
        e = error_mm(p, c.motion.tool_length, pp.dir);
      }
      return (p + e - pp.p).norm();
    };
    const PassStats st = run_pass(a, b, options.step, options.window, options.slack, options.tol_um,
                                  true, predicted, predicted);
    st.store(out.backward_points, out.backward_max_um, out.backward_rms_um, out.backward_max_line,
             out.backward_over_tol, out.backward_unmatched);
  }
  out.out_of_range_lookups = data.out_of_range_lookups;
  return out;
}

std::vector<std::string> verify_failures(const VerifyStats& s, double tol_um) {
  std::vector<std::string> why;
  if (s.points == 0) why.push_back("the compensated program has no feed points to check");
  if (s.backward_points == 0)
    why.push_back("the original program has no feed points to check against");
  if (s.unmatched)
    why.push_back(std::to_string(s.unmatched) +
                  " points of the compensated program have no feed motion of the original to "
                  "match");
  if (s.backward_unmatched)
    why.push_back(std::to_string(s.backward_unmatched) +
                  " points of the original have no feed motion of the compensated program to "
                  "match");
  const double max = std::max(s.max_um, s.backward_max_um);
  if (!(max <= tol_um) && !s.unmatched && !s.backward_unmatched)
    why.push_back("the max distance is beyond tol");
  return why;
}

}  // namespace abbe::compensate
