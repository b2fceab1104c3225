// The period of a chosen cycle refined on the exact ΔRSS
// (src/diagnose/parameter_scan.hpp, refine_period_exactly): a known period
// recovered from a start a fraction of a grid step off, zero in → nothing
// changes, the same period whatever the axis's zero, and a term that is
// not a cycle left alone. And a cycle's aliases kept only where the data
// do not reject them (confirm_aliases): the same samples on regular targets,
// a far worse fit at irregular ones.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "abbe/diagnose/selection.hpp"
#include "diagnose_test_problem.hpp"
#include "src/diagnose/choose_step.hpp"
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

// A laser line along X with n targets every `step` mm from 0, read along X:
// dx = amplitude·sin(2πx/P + 0.4) + noise.
Problem regular_line(int n, double step, double amplitude, double noise_um) {
  Problem pb;
  std::vector<double> y;
  std::mt19937_64 rng(5);
  std::normal_distribution<double> noise(0.0, noise_um);
  for (int k = 0; k < n; ++k) {
    const double x = k * step;
    PointContext pc;
    pc.p = pc.s = Eigen::Vector3d(x, 0.0, 0.0);
    pc.dir = {1, 1, 1};
    pc.set = "a";
    test::add_reading(pb, y, pc, Eigen::Vector3d::UnitX(),
                      amplitude * std::sin(6.283185307179586 * x / kTruePeriod + 0.4) + noise(rng));
  }
  test::finish_problem(pb, y, "a", {true, false, false}, Eigen::Vector3d::Zero(),
                       Eigen::Vector3d((n - 1) * step, 0.0, 0.0));
  return pb;
}

// On targets every h mm, f and 1/h − f give the same samples: the alias
// fits exactly as well and is kept. At 400 irregular targets the same
// alias removes far less and goes; the pick's own period stays.
TEST(DiagnosePeriodRefinement, AnAliasStaysOnlyWhereTheDataCannotRejectIt) {
  constexpr double kStep = 10.0;
  const double alias = 1.0 / (1.0 / kStep - 1.0 / kTruePeriod);  // 39.7 mm
  const double margin = 0.25 * 6.63;  // σ̂²·χ²₁(0.01), σ = 0.5 µm
  for (bool regular : {true, false}) {
    const Problem pb = regular ? regular_line(81, kStep, 3.0, 0.5) : line(0.0, 3.0, 0.5);
    const Fit f = datum(pb);
    Cached c = cycle_at(pb, f.Q, kTruePeriod);
    const double d = delta_rss(c.C, c.CtC, c.QtC, f.r);
    c.aliases = {alias};
    confirm_aliases(pb, f.Q, f.r, kGridStep, d, margin, c);
    EXPECT_EQ(c.term.period_mm, kTruePeriod);
    if (regular) {
      ASSERT_EQ(c.aliases.size(), 1u);
      EXPECT_NEAR(c.aliases[0] / alias, 1.0, 1e-3);  // refined: at its exact frequency
    } else {
      EXPECT_TRUE(c.aliases.empty());
    }
  }
}

// Zero in: nothing rejects an alias (both remove nothing), so it stays.
TEST(DiagnosePeriodRefinement, WithoutDataAnAliasIsNotRejected) {
  const Problem pb = line(0.0, 0.0, 0.0);
  const Fit f = datum(pb);
  Cached c = cycle_at(pb, f.Q, kTruePeriod);
  c.aliases = {21.0};
  confirm_aliases(pb, f.Q, f.r, kGridStep, 0.0, 1e-6, c);
  EXPECT_EQ(c.aliases.size(), 1u);
}

// Which axes keep the periodogram's aliases as found: 81 regular targets
// along X are levels (≤ alias_levels), 400 irregular ones are not; Y and Z,
// at 0 throughout, are one level.
TEST(DiagnosePeriodRefinement, AnAxisOfFewLevelsKeepsItsAliasesAsFound) {
  for (bool regular : {true, false}) {
    const Problem pb = regular ? regular_line(81, 10.0, 3.0, 0.5) : line(0.0, 3.0, 0.5);
    SelectionOptions o;
    o.alias_levels = 100;
    const CandidateSet cs = build_candidates(pb, CandidateOptions{});
    const PathState ps(pb, cs, o, datum(pb).Q);
    EXPECT_EQ(ps.levelled[0], regular);
    EXPECT_TRUE(ps.levelled[1]);
    EXPECT_TRUE(ps.levelled[2]);
    o.alias_levels = 80;  // one level fewer than the regular line has
    EXPECT_FALSE(PathState(pb, cs, o, datum(pb).Q).levelled[0]);
  }
}

}  // namespace
}  // namespace abbe::diagnose::selection
