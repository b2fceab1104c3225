#include "abbe/diagnose/candidates.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>

#include "coverage.hpp"

namespace abbe::diagnose {
namespace {

// The multiple correlation R of a reversal's growth along axis j,
// g = sign(v_j)·x with x = (s_j − mid)/half, with the position x (a scale)
// and the jump sign(v_j), all after their mean per set (the datum), over
// the observations of direction i: R² is the share of g's variance the two
// fit together; 1 where the position or the jump is constant there. (The
// time is left to the data: over one run there and back a drift linear in
// t is a jump plus a growth, and the rival checks compare them; leaving
// the growth out where it follows t lets another term take it.)
double growth_correlation(const Problem& pb, int j, int i) {
  struct Sums {
    double n = 0.0;
    Eigen::Vector3d m = Eigen::Vector3d::Zero();  // g, x, sign(v_j)
    Eigen::Matrix3d mm = Eigen::Matrix3d::Zero();
  };
  std::map<std::string, Sums> per_set;
  const auto ji = static_cast<std::size_t>(j);
  for (const Observation& ob : pb.obs) {
    if (std::abs(ob.u[i]) <= 1e-9) continue;
    const PointContext& pc = pb.points[ob.point];
    const double v = static_cast<double>(pc.dir[ji]);
    const double x = (pc.s[j] - pb.travel_mid[j]) / std::max(pb.travel_half[j], 1e-9);
    const Eigen::Vector3d row(v * x, x, v);
    Sums& s = per_set[pc.set];
    s.n += 1.0;
    s.m += row;
    s.mm += row * row.transpose();
  }
  Eigen::Matrix3d S = Eigen::Matrix3d::Zero();  // the scatter about each set's mean
  for (const auto& [set, s] : per_set) S += s.mm - s.m * s.m.transpose() / s.n;
  if (!(S(0, 0) > 1e-12) || !(S(1, 1) > 1e-12) || !(S(2, 2) > 1e-12)) return 1.0;
  const Eigen::Vector2d b = S.block<2, 1>(1, 0);
  const Eigen::Vector2d beta =
      S.bottomRightCorner<2, 2>().completeOrthogonalDecomposition().solve(b);
  return std::sqrt(std::clamp(b.dot(beta) / S(0, 0), 0.0, 1.0));
}

}  // namespace

CandidateSet build_candidates(const Problem& pb, const CandidateOptions& o) {
  CandidateSet cs;
  auto varies = [&](int v) {
    const auto i = static_cast<std::size_t>(v);
    return pb.var_hi[i] - pb.var_lo[i] > 1e-9;
  };
  // What a term of direction i can be seen by: the variables' range and the
  // direction signs over the observations that measure direction i (a laser
  // line along X measures d_x at one y and z only: a d_x ∝ y is its datum);
  // a reversal of j needs both signs of v_j there (else it is a constant).
  const Coverage seen(pb);
  bool model_delta = false;
  std::array<bool, 3> eps{false, false, false};
  for (const PointContext& pc : pb.points) {
    for (std::size_t j = 0; j < 3; ++j)
      if (pc.eps_urad[j].squaredNorm() > 0.0) eps[j] = true;
    if (pc.model_delta_um.squaredNorm() > 1e-18) model_delta = true;
  }
  auto present = [&](int i) { return pb.direction_present[static_cast<std::size_t>(i)]; };
  auto add = [&](Term t) {
    cs.fixed.push_back(std::move(t));
    ++cs.named_tests;
  };

  if (model_delta) {
    Term t;
    t.kind = TermKind::model_choice;
    t.other_model = pb.other_model;
    add(t);
  }
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) {
      if (!present(i)) continue;
      if (seen.varies_in(j, i)) add(position_term(j, i));
      if (seen.reverses_in(j, i)) {
        Term t;
        t.kind = TermKind::reversal;
        t.axis = j;
        t.direction = i;
        add(t);
        // Growing along its travel (in its own direction only: a jump
        // across, d_i when j reverses, that also grows is not a catalogue
        // shape).
        if (o.growing_reversal && i == j && seen.varies_in(j, i) &&
            growth_correlation(pb, j, i) <= o.max_growth_correlation) {
          t.degree = 1;
          t.centre = pb.travel_mid;
          t.half = pb.travel_half;
          add(t);
        }
      }
      for (int k = j + 1; k < 3; ++k)
        if (seen.varies_in(j, i) && seen.varies_in(k, i)) {
          Term t;
          t.kind = TermKind::coupling;
          t.axis = j;
          t.with_axis = k;
          t.direction = i;
          t.centre = pb.travel_mid;
          t.half = pb.travel_half;
          add(t);
        }
      if (seen.varies_in(j, i)) {
        ScanFamily f;
        f.base.kind = TermKind::cyclic;
        f.base.axis = j;
        f.base.direction = i;
        // Frequencies evenly spaced at a quarter of 1/span: no peak falls between two.
        const double span =
            pb.var_hi[static_cast<std::size_t>(j)] - pb.var_lo[static_cast<std::size_t>(j)];
        const double df = 0.25 / std::max(span, 1e-3);
        // A cycle is named only where the travel holds two of its periods
        // (max_period_span_share): over less, a sinusoid is a bow or a
        // slope of the axis, not a period (a scale of X on a 50 mm ballbar
        // circle is a cycle of 64 mm as well).
        const double max_period = std::min(o.max_period_mm, o.max_period_span_share * span);
        for (double fr = 1.0 / max_period; fr <= 1.0 / o.min_period_mm; fr += df)
          f.grid.push_back(1.0 / fr);
        if (f.grid.size() >= 2) {
          cs.named_tests += static_cast<int>(f.grid.size());
          cs.scanned.push_back(std::move(f));
        }
      }
    }
    if (eps[static_cast<std::size_t>(j)])
      for (int k = 0; k < 3; ++k) {
        Term t;
        t.kind = TermKind::arm_offset;
        t.axis = j;
        t.direction = k;
        add(t);
      }
  }
  for (int i = 0; i < 3; ++i) {
    if (!present(i) || !seen.varies_in(3, i)) continue;
    for (int w = -1; w < 3; ++w) {
      if (w >= 0 && !seen.varies_in(w, i)) continue;
      ScanFamily f;
      f.base.kind = TermKind::thermal_drift;
      f.base.axis = w >= 0 ? w : i;
      f.base.direction = i;
      f.base.with_axis = w;
      f.grid = o.tau_s;
      cs.named_tests += static_cast<int>(f.grid.size());
      cs.scanned.push_back(std::move(f));
    }
  }
  // Setup: the offset per set and direction is the datum (always fitted);
  // a rotation per set about each axis around the set's centroid is a
  // candidate, except for a plate (a set in one plane whose normal direction
  // is not measured), where the rotation in the plane is datum too.
  for (const std::string& set : pb.sets) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
    double n = 0.0;
    for (const PointContext& pc : pb.points)
      if (pc.set == set) {
        c += pc.p;
        lo = lo.cwiseMin(pc.p);
        hi = hi.cwiseMax(pc.p);
        n += 1.0;
      }
    c /= std::max(n, 1.0);
    for (int i = 0; i < 3; ++i) {
      if (!present(i)) continue;
      Term t;
      t.kind = TermKind::setup_offset;
      t.axis = i;
      t.direction = i;
      t.set = set;
      cs.datum.push_back(t);
    }
    for (int a = 0; a < 3; ++a) {
      // A rotation about a moves the directions ⟂ a along the other two coordinates.
      const int b = (a + 1) % 3, d = (a + 2) % 3;
      const bool visible = (present(b) && varies(d)) || (present(d) && varies(b));
      if (!visible) continue;
      Term t;
      t.kind = TermKind::setup_rotation;
      t.axis = a;
      t.set = set;
      t.centre = c;
      const bool plate = hi[a] - lo[a] < 1e-9 && !present(a) && present(b) && present(d);
      if (plate) {
        cs.datum.push_back(t);
      } else {
        add(t);
      }
    }
  }
  // Unexplained: smooth functions of one variable or of a pair.
  for (int v = 0; v < 4; ++v) {
    if (!varies(v)) continue;
    Term t;
    t.kind = TermKind::unexplained;
    t.vars = {v};
    t.degree = o.single_degree;
    for (std::size_t k = 0; k < 4; ++k) {
      t.lo[k] = pb.var_lo[k];
      t.hi[k] = pb.var_hi[k] > pb.var_lo[k] ? pb.var_hi[k] : pb.var_lo[k] + 1.0;
    }
    cs.generic.push_back(t);
    for (int w = v + 1; w < 4; ++w) {
      if (!varies(w)) continue;
      Term p = t;
      p.vars = {v, w};
      p.degree = o.pair_degree;
      cs.generic.push_back(p);
    }
  }
  int dirs = 0;
  for (int i = 0; i < 3; ++i) dirs += present(i) ? 1 : 0;
  cs.generic_tests = static_cast<int>(cs.generic.size()) * dirs;
  return cs;
}

}  // namespace abbe::diagnose
