// The period of a chosen cycle refined on the exact ΔRSS
// (src/diagnose/parameter_scan.hpp, refine_period_exactly): a known period
// recovered from a start a fraction of a grid step off, zero in → nothing
// changes, the same period whatever the axis's zero, and a term that is
// not a cycle left alone.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "abbe/diagnose/selection.hpp"
#include "diagnose_test_problem.hpp"
#include "src/diagnose/parameter_scan.hpp"

namespace abbe::diagnose::selection {
namespace {

constexpr double kSpan = 800.0;             // mm of travel along X
constexpr double kGridStep = 0.25 / kSpan;  // the scan's frequency step (candidates.cpp)
constexpr double kTruePeriod = 13.37;       // mm

// One laser line along X: 400 targets at irregular positions in
// [zero, zero + 800], read along X; dx = amplitude·sin(2πx/P + 0.4) + noise.
Problem line(double zero, double amplitude, double noise_um) {
  return test::sine_line(zero, kSpan, 400, kTruePeriod, amplitude, 0.4, noise_um, 11, 12);
}

struct Fit {
  Mat Q;  // the datum: one offset
  Vec r;  // the data without their mean
};
Fit datum(const Problem& pb) {
  Fit f;
  const auto n = pb.y.size();
  f.Q = Mat::Constant(n, 1, 1.0 / std::sqrt(static_cast<double>(n)));
  f.r = pb.y - f.Q * (f.Q.transpose() * pb.y);
  return f;
}

Cached cycle_at(const Problem& pb, const Mat& Q, double period) {
  Term t;
  t.kind = TermKind::cyclic;
  t.axis = 0;
  t.direction = 0;
  t.period_mm = period;
  Cached c{t, term_columns(pb, t), Mat(), Mat(), {}};
  c.CtC = c.C.transpose() * c.C;
  c.QtC = Q.transpose() * c.C;
  return c;
}

// A start 0.4 of a scan step off the true frequency (what a periodogram's
// grid and parabola leave) ends within 10⁻⁴ of the true period and removes
// more than it did.
TEST(DiagnosePeriodRefinement, RecoversAKnownPeriod) {
  const Problem pb = line(0.0, 3.0, 0.1);
  const Fit f = datum(pb);
  Cached c = cycle_at(pb, f.Q, 1.0 / (1.0 / kTruePeriod + 0.4 * kGridStep));
  const double before = delta_rss(c.C, c.CtC, c.QtC, f.r);
  refine_period_exactly(pb, f.Q, f.r, kGridStep, c);
  EXPECT_NEAR(c.term.period_mm / kTruePeriod, 1.0, 1e-4);
  const double after = delta_rss(c.C, c.CtC, c.QtC, f.r);
  EXPECT_GT(after, before);
  // The products are those of the new columns.
  EXPECT_LT((c.QtC - f.Q.transpose() * term_columns(pb, c.term)).norm(), 1e-9);
}

// Zero in: nothing to remove, the term stays as it came.
TEST(DiagnosePeriodRefinement, ZeroInLeavesThePeriod) {
  const Problem pb = line(0.0, 0.0, 0.0);
  const Fit f = datum(pb);
  const double start = 1.0 / (1.0 / kTruePeriod + 0.4 * kGridStep);
  Cached c = cycle_at(pb, f.Q, start);
  refine_period_exactly(pb, f.Q, f.r, kGridStep, c);
  EXPECT_EQ(c.term.period_mm, start);
}

// Machine zero is a free constant: the same data at another zero give the
// same period (the phase takes the shift).
TEST(DiagnosePeriodRefinement, TheAxisZeroDoesNotMoveThePeriod) {
  double period[2];
  for (int k = 0; k < 2; ++k) {
    const Problem pb = line(k == 0 ? 0.0 : -437.25, 2.0, 0.5);
    const Fit f = datum(pb);
    Cached c = cycle_at(pb, f.Q, 1.0 / (1.0 / kTruePeriod - 0.3 * kGridStep));
    refine_period_exactly(pb, f.Q, f.r, kGridStep, c);
    period[k] = c.term.period_mm;
  }
  EXPECT_NEAR(period[0], period[1], 1e-6 * period[0]);
  EXPECT_NEAR(period[0] / kTruePeriod, 1.0, 1e-3);
}

// Only cycles have a period to refine.
TEST(DiagnosePeriodRefinement, AnotherKindIsLeftAlone) {
  const Problem pb = line(0.0, 3.0, 0.1);
  const Fit f = datum(pb);
  Term t;
  t.kind = TermKind::scale;
  t.axis = 0;
  t.direction = 0;
  Cached c{t, term_columns(pb, t), Mat(), Mat(), {}};
  c.CtC = c.C.transpose() * c.C;
  c.QtC = f.Q.transpose() * c.C;
  const Mat C0 = c.C;
  refine_period_exactly(pb, f.Q, f.r, kGridStep, c);
  EXPECT_EQ(c.term.kind, TermKind::scale);
  EXPECT_EQ((c.C - C0).norm(), 0.0);
}

}  // namespace
}  // namespace abbe::diagnose::selection
