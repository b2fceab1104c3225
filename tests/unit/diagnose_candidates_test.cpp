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
  const CandidateSet cs = build_candidates(test::two_laser_lines(true), CandidateOptions{});
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
  const CandidateSet cs = build_candidates(test::two_laser_lines(false), CandidateOptions{});
  EXPECT_TRUE(has_fixed(cs, TermKind::squareness, 1, 0));
  EXPECT_TRUE(has_fixed(cs, TermKind::squareness, 0, 1));
  EXPECT_TRUE(has_fixed(cs, TermKind::reversal, 1, 0));
  EXPECT_TRUE(has_fixed(cs, TermKind::coupling, 0, 0));
  EXPECT_TRUE(has_scanned(cs, TermKind::cyclic, 1, 0));
  EXPECT_TRUE(has_scanned(cs, TermKind::thermal_drift, 1, 0, 1));
  EXPECT_GT(cs.named_tests,
            build_candidates(test::two_laser_lines(true), CandidateOptions{}).named_tests);
}

}  // namespace
}  // namespace abbe::diagnose
