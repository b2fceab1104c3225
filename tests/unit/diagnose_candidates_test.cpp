// The candidates a design can see (candidates.hpp): a term of direction i
// is a candidate only where the observations that measure direction i see
// its variables vary (and, for a reversal, its axis move both ways). Laser
// lines along X and along Y (each measuring its own axis) against the same
// points measured in every direction.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "abbe/diagnose/candidates.hpp"
#include "diagnose_test_problem.hpp"

namespace abbe::diagnose {
namespace {

// Two lines, there and back: along X at y = 100 and along Y at x = 200, z = 0.
// `line_only`: each point measured along its line; else in X and Y both.
Problem two_lines(bool line_only) {
  Problem pb;
  std::vector<double> y;
  double t = 0.0;
  for (int a = 0; a < 2; ++a)
    for (int way : {1, -1})
      for (int k = 0; k <= 10; ++k) {
        const double s = 40.0 * (way > 0 ? k : 10 - k);
        PointContext pc;
        pc.p = a == 0 ? Eigen::Vector3d(s, 100.0, 0.0) : Eigen::Vector3d(200.0, s, 0.0);
        pc.s = pc.p;
        pc.dir = {a == 0 ? way : 1, a == 1 ? way : 1, 0};
        pc.t = t;
        t += 5.0;
        pc.set = "a";
        for (int i = 0; i < 2; ++i)
          if (!line_only || i == a) test::add_reading(pb, y, pc, Eigen::Vector3d::Unit(i), 0.0);
      }
  test::finish_problem(pb, y, "a", {true, true, false}, Eigen::Vector3d(0.0, 0.0, 0.0),
                       Eigen::Vector3d(400.0, 400.0, 0.0));
  pb.var_lo[3] = 0.0;
  pb.var_hi[3] = t;
  return pb;
}

bool has_fixed(const CandidateSet& cs, TermKind kind, int axis, int direction) {
  return std::any_of(cs.fixed.begin(), cs.fixed.end(), [&](const Term& t) {
    return t.kind == kind && t.axis == axis && t.direction == direction;
  });
}

bool has_scanned(const CandidateSet& cs, TermKind kind, int axis, int direction, int with = -1) {
  return std::any_of(cs.scanned.begin(), cs.scanned.end(), [&](const ScanFamily& f) {
    return f.base.kind == kind && f.base.axis == axis && f.base.direction == direction &&
           (kind != TermKind::thermal_drift || f.base.with_axis == with);
  });
}

TEST(DiagnoseCandidates, ALineSeesOnlyWhatVariesAlongIt) {
  const CandidateSet cs = build_candidates(two_lines(true), CandidateOptions{});
  // Along X: d_x ∝ x, its reversal, its cycles, a drift and one ∝ x.
  EXPECT_TRUE(has_fixed(cs, TermKind::scale, 0, 0));
  EXPECT_TRUE(has_fixed(cs, TermKind::reversal, 0, 0));
  EXPECT_TRUE(has_scanned(cs, TermKind::cyclic, 0, 0));
  EXPECT_TRUE(has_scanned(cs, TermKind::thermal_drift, 0, 0, -1));
  EXPECT_TRUE(has_scanned(cs, TermKind::thermal_drift, 0, 0, 0));
  // d_x as a function of y is a constant on the X line: its datum.
  EXPECT_FALSE(has_fixed(cs, TermKind::squareness, 1, 0));
  EXPECT_FALSE(has_fixed(cs, TermKind::reversal, 1, 0));
  EXPECT_FALSE(has_fixed(cs, TermKind::coupling, 0, 0));
  EXPECT_FALSE(has_scanned(cs, TermKind::cyclic, 1, 0));
  EXPECT_FALSE(has_scanned(cs, TermKind::thermal_drift, 1, 0, 1));  // drift ∝ y in d_x
  // And the same for d_y along the Y line.
  EXPECT_TRUE(has_fixed(cs, TermKind::scale, 1, 1));
  EXPECT_TRUE(has_fixed(cs, TermKind::reversal, 1, 1));
  EXPECT_FALSE(has_fixed(cs, TermKind::squareness, 0, 1));
  EXPECT_FALSE(has_scanned(cs, TermKind::thermal_drift, 0, 1, 0));
}

TEST(DiagnoseCandidates, PointsMeasuredInEveryDirectionKeepTheCrossTerms) {
  const CandidateSet cs = build_candidates(two_lines(false), CandidateOptions{});
  EXPECT_TRUE(has_fixed(cs, TermKind::squareness, 1, 0));
  EXPECT_TRUE(has_fixed(cs, TermKind::squareness, 0, 1));
  EXPECT_TRUE(has_fixed(cs, TermKind::reversal, 1, 0));
  EXPECT_TRUE(has_fixed(cs, TermKind::coupling, 0, 0));
  EXPECT_TRUE(has_scanned(cs, TermKind::cyclic, 1, 0));
  EXPECT_TRUE(has_scanned(cs, TermKind::thermal_drift, 1, 0, 1));
  EXPECT_GT(cs.named_tests, build_candidates(two_lines(true), CandidateOptions{}).named_tests);
}

}  // namespace
}  // namespace abbe::diagnose
