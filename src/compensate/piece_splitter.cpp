#include "piece_splitter.hpp"

#include <algorithm>

#include "abbe/compensate/motion_path.hpp"

namespace abbe::compensate::detail {

using Eigen::Vector3d;

bool piece_within(const gcode::Motion& m, const std::vector<SolvedPoint>& sp, std::size_t a,
                  std::size_t b, double tol) {
  if (b <= a + 1) return true;
  const Vector3d ca = sp[a].n + sp[a].delta_out, cb = sp[b].n + sp[b].delta;
  if (m.kind != gcode::MotionKind::arc) {
    // A segment: distances to the line through its ends (all points lie
    // near the segment, so the infinite line is the same here).
    const Vector3d u = cb - ca;
    const double l2 = u.squaredNorm();
    for (std::size_t k = a + 1; k < b; ++k) {
      const Vector3d w = sp[k].n + sp[k].delta - ca;
      const double s = l2 > 0.0 ? std::clamp(w.dot(u) / l2, 0.0, 1.0) : 0.0;
      if ((w - s * u).squaredNorm() > tol * tol) return false;
    }
    return true;
  }
  gcode::Motion piece = m;
  piece.start = ca;
  piece.end = cb;
  piece.center = m.center + 0.5 * (sp[a].delta_out + sp[b].delta);
  const int normal = gcode::plane_axes(m.plane)[2];
  piece.center[normal] = piece.start[normal];
  if (a != 0 || b + 1 != sp.size()) piece.rotation = m.rotation > 0 ? 1 : -1;
  const MotionPath path(piece);
  for (std::size_t k = a + 1; k < b; ++k)
    if (path.distance_near(sp[k].n + sp[k].delta) > tol) return false;
  return true;
}

void split_into_pieces(const gcode::Motion& m, const std::vector<SolvedPoint>& sp, double tol,
                       std::vector<std::size_t>& breaks) {
  breaks.clear();
  bool forced = false;
  for (const auto& x : sp) forced = forced || x.reversal;
  if (!forced && piece_within(m, sp, 0, sp.size() - 1, tol)) breaks.push_back(sp.size() - 1);
  for (std::size_t a = 0; breaks.empty() || breaks.back() + 1 < sp.size();) {
    // Longest b from a: grow while the piece stays within tol (the check
    // of a piece costs its length, so grow by doubling, then bisect).
    std::size_t b = a + 1;
    std::size_t limit = sp.size() - 1;
    for (std::size_t k = a + 1; k < limit; ++k)
      if (sp[k].reversal) {
        limit = k;
        break;
      }
    if (b < limit) {
      std::size_t good = b, step = 1;
      while (good + step <= limit && piece_within(m, sp, a, good + step, tol)) {
        good += step;
        step *= 2;
      }
      std::size_t bad = std::min(limit + 1, good + step);
      while (bad - good > 1) {
        const std::size_t mid = good + (bad - good) / 2;
        if (piece_within(m, sp, a, mid, tol))
          good = mid;
        else
          bad = mid;
      }
      b = good;
    }
    breaks.push_back(b);
    a = b;
  }
}

std::size_t merge_short_pieces(const gcode::Motion& m, const std::vector<SolvedPoint>& sp,
                               double len, double min_len, double tol,
                               std::vector<std::size_t>& breaks) {
  if (min_len <= 0.0 || breaks.size() < 2) return 0;
  const bool arc = m.kind == gcode::MotionKind::arc;
  auto piece_length = [&](std::size_t a, std::size_t b) {
    if (arc) return (sp[b].t - sp[a].t) * len;
    return ((sp[b].n + sp[b].delta) - (sp[a].n + sp[a].delta_out)).norm();
  };
  std::size_t kept = 0;
  for (std::size_t j = 0; j < breaks.size() && breaks.size() > 1;) {
    const std::size_t a = j == 0 ? 0 : breaks[j - 1], b = breaks[j];
    if (piece_length(a, b) >= min_len) {
      ++j;
      continue;
    }
    const bool forced_end = sp[b].reversal || j + 1 == breaks.size();
    if (!forced_end && piece_within(m, sp, a, breaks[j + 1], tol)) {
      breaks.erase(breaks.begin() + static_cast<std::ptrdiff_t>(j));
      continue;  // the merged piece is checked again
    }
    const std::size_t prev_a = j >= 2 ? breaks[j - 2] : 0;
    if (j > 0 && !sp[a].reversal && piece_within(m, sp, prev_a, b, tol)) {
      breaks.erase(breaks.begin() + static_cast<std::ptrdiff_t>(j - 1));
      --j;
      continue;
    }
    ++kept;
    ++j;
  }
  return kept;
}

}  // namespace abbe::compensate::detail
