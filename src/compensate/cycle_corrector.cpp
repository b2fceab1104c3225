#include "cycle_corrector.hpp"

#include <cmath>
#include <optional>

namespace abbe::compensate::detail {
namespace {

using Eigen::Vector3d;
constexpr char kAxis[3] = {'X', 'Y', 'Z'};

}  // namespace

void CycleCorrector::correct(const CycleBlock& c, CycleHost& host, BlockEditor& editor,
                             std::vector<std::string>& pieces, Vector3d& cmd,
                             CompensateSummary& summary) {
  const auto ax = gcode::plane_axes(c.plane);
  const int n = ax[2];
  if (!in_series_) initial_level_delta_ = c.delta[n];
  in_series_ = true;
  const double level = c.incremental ? initial_level_delta_ : 0.0;
  const gcode::Word* l = c.incremental ? find_word(c.block, 'L') : nullptr;
  if (l && l->value > 1.0) {
    repeated(c, host, editor, pieces, cmd, static_cast<int>(std::lround(l->value)), level, summary);
  } else {
    // The hole bottom: the feed end farthest from where the cycle leaves the tool.
    std::optional<std::size_t> hole;
    double far = -1.0;
    for (std::size_t i = 0; i < c.motions.size(); ++i) {
      if (c.motions[i].kind != gcode::MotionKind::linear || c.points[i].empty()) continue;
      const double dist = (c.motions[i].end - c.tip_after).norm();
      if (dist > far) {
        far = dist;
        hole = i;
      }
    }
    if (hole) {
      const Vector3d d = host.solve(c.points[*hole].back());
      const Vector3d h = host.prog(c.motions[*hole].end);
      for (int k = 0; k < 2; ++k) {
        const int a = ax[static_cast<std::size_t>(k)];
        cmd[a] = host.set_abs(editor, kAxis[a], h[a] + d[a] / c.unit, cmd[a], cmd[a], c.incremental,
                              true);
      }
      // The depth word: absolute in G90; in G91 relative to the R plane, which
      // does not move, so it moves by the correction along the drill axis.
      const gcode::Word* zw = find_word(c.block, kAxis[n]);
      const double cc = c.incremental ? (zw ? zw->value : written_depth_) : h[n];
      const double v =
          editor.set(kAxis[n], cc + (d[n] - level) / c.unit, cc + depth_delta_ / c.unit, true);
      depth_delta_ = (v - cc) * c.unit;
    }
  }
  // The cycle leaves the tool at its clearance height: the initial level
  // (G98), which carries the correction of the point where the series
  // began, or the R plane (G99), nominal in G90 and relative to the initial
  // level in G91. The written depth word is the modal one afterwards.
  if (const gcode::Word* w = find_word(c.block, kAxis[n])) written_depth_ = w->value;
  const double clearance = c.retract_to_r && !c.incremental ? 0.0 : initial_level_delta_;
  cmd[n] = host.prog(c.tip_after)[n] + clearance / c.unit;
}

// G91 canned cycle with L repeats. One increment serves every hole, so the
// holes cannot all be corrected as written. With G98 (retract to the initial
// level) the block is expanded: the L word goes, the block drills the first
// hole and inserted lines (X, Y increments and, where it changes, the depth
// Z) drill the others — a modal cycle repeats at each new position exactly
// as its L repeats would, so every hole gets its own correction. With G99 a
// continued block would take R from the R plane in rs274ngc, not from the
// initial level; there the holes get the correction δ_before + k·g
// (k = 1..L), g the least-squares fit to the corrections δ_k at the bottoms,
// and the depth the mean of δ_k − δ_before.
void CycleCorrector::repeated(const CycleBlock& c, CycleHost& host, BlockEditor& editor,
                              std::vector<std::string>& pieces, Vector3d& cmd, int repeats,
                              double level, CompensateSummary& summary) {
  const auto ax = gcode::plane_axes(c.plane);
  const int n = ax[2];
  std::vector<Vector3d> holes, bottoms;  // corrections and nominal points at the bottoms
  for (std::size_t i = 0; i < c.motions.size(); ++i) {
    if (c.motions[i].kind != gcode::MotionKind::linear || c.points[i].empty()) continue;
    // The feed into a hole: the drill axis moves; its end is the bottom
    // when the next motion leaves it (a retract).
    const Vector3d d = c.motions[i].end - c.motions[i].start;
    if (std::abs(d[n]) <= 0.0) continue;
    const bool bottom = i + 1 == c.motions.size() ||
                        (c.motions[i + 1].end[n] - c.motions[i + 1].start[n]) * d[n] < 0.0;
    if (bottom) {
      holes.push_back(host.solve(c.points[i].back()));
      bottoms.push_back(c.motions[i].end);
    }
  }
  if (holes.size() != static_cast<std::size_t>(repeats)) {
    ++summary.uncompensated_blocks;
    host.warn(c.block.line, "canned cycle with L repeats in G91: holes left uncompensated");
    return;
  }
  const gcode::Word* zw = find_word(c.block, kAxis[n]);
  const double cc = zw ? zw->value : written_depth_;
  bool exact = true;  // as written, every hole is where it must be
  for (const auto& h : holes)
    for (int k = 0; k < 3; ++k)
      exact = exact && round_to((h[k] - (k == n ? level : c.delta[k])) / c.unit, c.decimals) == 0.0;
  if (exact) {  // the increments as written: the tool ends L of them on
    for (int k = 0; k < 2; ++k) {
      const int a = ax[static_cast<std::size_t>(k)];
      const gcode::Word* w = find_word(c.block, kAxis[a]);
      cmd[a] += static_cast<double>(repeats) * (w ? w->value : 0.0);
    }
    return;
  }
  if (!c.retract_to_r) {
    editor.remove('L');
    const char* sep = editor.spaced() ? " " : "";
    double cc_written = cc + depth_delta_ / c.unit;
    for (std::size_t k = 0; k < holes.size(); ++k) {
      const Vector3d h = host.prog(bottoms[k]) + holes[k] / c.unit;
      const double cc_k = cc + (holes[k][n] - level) / c.unit;
      if (k == 0) {
        for (int i = 0; i < 2; ++i) {
          const int a = ax[static_cast<std::size_t>(i)];
          cmd[a] = host.set_abs(editor, kAxis[a], h[a], cmd[a], cmd[a], true, true);
        }
        cc_written = editor.set(kAxis[n], cc_k, cc_written, true);
        continue;
      }
      std::string line;
      for (int i = 0; i < 2; ++i) {
        const int a = ax[static_cast<std::size_t>(i)];
        const double v = round_to(h[a] - cmd[a], c.decimals);
        append_word(line, line.empty() ? "" : sep, kAxis[a], v, c.plain, c.decimals);
        cmd[a] += v;
      }
      const double z = round_to(cc_k, c.decimals);
      if (z != round_to(cc_written, c.decimals)) {
        append_word(line, sep, kAxis[n], z, c.plain, c.decimals);
        cc_written = z;
      }
      pieces.push_back(line);
    }
    depth_delta_ = (cc_written - cc) * c.unit;
    return;
  }
  ++summary.shared_increment_blocks;
  host.warn(c.block.line,
            "canned cycle with L repeats in G91 G99: one increment serves every hole "
            "(least-squares correction)");
  Vector3d num = Vector3d::Zero();
  double den = 0.0;
  double mean_n = 0.0;
  for (std::size_t k = 0; k < holes.size(); ++k) {
    const double kk = static_cast<double>(k + 1);
    num += kk * (holes[k] - c.delta);
    den += kk * kk;
    mean_n += (holes[k][n] - level) / static_cast<double>(holes.size());
  }
  const Vector3d g = num / den;
  for (int k = 0; k < 2; ++k) {
    const int a = ax[static_cast<std::size_t>(k)];
    const gcode::Word* w = find_word(c.block, kAxis[a]);
    const double inc = (w ? w->value : 0.0) + g[a] / c.unit;
    const double v = editor.set(kAxis[a], inc, w ? w->value : 0.0, true);
    cmd[a] += static_cast<double>(repeats) * v;
  }
  if (zw) editor.set(kAxis[n], zw->value + mean_n / c.unit, zw->value, false);
}

}  // namespace abbe::compensate::detail
