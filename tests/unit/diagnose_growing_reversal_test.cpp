// A reversal that grows along its travel (effects/reversal.cpp, degree 1):
// its two columns by hand, its overlay entry, where the design lets it be a
// candidate (candidates.cpp: its growth told from a scale and from the jump)
// and that the selection names it — with its growth and that growth's
// uncertainty — only where the data hold a growth.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "abbe/diagnose/candidates.hpp"
#include "abbe/diagnose/overlay.hpp"
#include "abbe/diagnose/selection.hpp"
#include "abbe/io/input_error.hpp"
#include "diagnose_test_problem.hpp"

namespace abbe::diagnose {
namespace {

Term growing_reversal_x() {
  Term t;
  t.kind = TermKind::reversal;
  t.axis = 0;
  t.direction = 0;
  t.degree = 1;
  t.centre = Eigen::Vector3d(100.0, 0.0, 0.0);
  t.half = Eigen::Vector3d(50.0, 1.0, 1.0);
  return t;
}

PointContext at_x(double x, int dir) {
  PointContext pc;
  pc.p = pc.s = Eigen::Vector3d(x, 0.0, 0.0);
  pc.dir = {dir, 0, 0};
  return pc;
}

TEST(DiagnoseGrowingReversal, ColumnsByHand) {
  Term t = growing_reversal_x();
  ASSERT_EQ(t.columns(), 2);
  Eigen::Matrix<double, 3, Eigen::Dynamic> g(3, 2);
  // At the travel's end, approached in +X: half the jump, half its growth.
  t.basis(at_x(150.0, 1), g);
  EXPECT_DOUBLE_EQ(g(0, 0), 0.5);
  EXPECT_DOUBLE_EQ(g(0, 1), 0.5);
  EXPECT_DOUBLE_EQ(g.bottomRows(2).norm(), 0.0);
  // At its start, approached in −X: the jump's sign and the growth's both turn.
  t.basis(at_x(50.0, -1), g);
  EXPECT_DOUBLE_EQ(g(0, 0), -0.5);
  EXPECT_DOUBLE_EQ(g(0, 1), 0.5);
  // Zero in, zero out; a jump of 4 µm that is 1 µm larger at the end.
  t.coef = {0.0, 0.0};
  EXPECT_EQ(t.evaluate(at_x(150.0, 1)), Eigen::Vector3d::Zero());
  t.coef = {4.0, 1.0};
  EXPECT_DOUBLE_EQ(t.evaluate(at_x(150.0, 1)).x(), 2.5);
  EXPECT_DOUBLE_EQ(t.evaluate(at_x(150.0, -1)).x(), -2.5);
  EXPECT_DOUBLE_EQ(t.evaluate(at_x(100.0, 1)).x(), 2.0);  // the middle: the jump alone
  // The jump between the two ways at x is 4 + 1·(x − 100)/50.
  EXPECT_DOUBLE_EQ(t.evaluate(at_x(75.0, 1)).x() - t.evaluate(at_x(75.0, -1)).x(), 3.5);
  EXPECT_EQ(t.label(), "reversal X→X growing along x");
  ASSERT_EQ(t.params().size(), 2u);
  EXPECT_EQ(t.params()[1].first, "growth_um");
  EXPECT_EQ(t.params()[1].second, 1.0);
  t.stderr_ = {0.1, 0.2};
  ASSERT_EQ(t.param_stderr().size(), 2u);
  EXPECT_EQ(t.param_stderr()[1].second, 0.2);
  // The text table shows the jump ± u; the description the growth ± u.
  EXPECT_NE(t.description().find("+1.00 ± 0.2 µm more at the travel's end (x = 150.0 mm)"),
            std::string::npos)
      << t.description();
  // Without its growth it is the plain reversal, one column.
  t.degree = 0;
  EXPECT_EQ(t.columns(), 1);
  EXPECT_EQ(t.label(), "reversal X→X");
}

TEST(DiagnoseGrowingReversal, OverlayRoundTripAndBadField) {
  Term t = growing_reversal_x();
  t.coef = {4.0, 1.0};
  Term plain;
  plain.kind = TermKind::reversal;
  plain.axis = plain.direction = 1;
  plain.coef = {2.0};
  Overlay ov;
  ov.base_model = "ae-arm";
  ov.machine = "test";
  ov.terms = {t, plain};
  const std::string yaml = ov.to_yaml();
  EXPECT_NE(yaml.find("growing: true"), std::string::npos) << yaml;
  const Overlay back = Overlay::parse(yaml, "g.yaml");
  ASSERT_EQ(back.terms.size(), 2u);
  EXPECT_EQ(back.terms[0].degree, 1);
  EXPECT_EQ(back.terms[0].centre, t.centre);
  EXPECT_EQ(back.terms[0].half, t.half);
  EXPECT_EQ(back.terms[1].degree, 0);  // an entry without `growing`: the plain reversal
  EXPECT_EQ(back.to_yaml(), yaml);

  std::string bad = yaml;
  bad.replace(bad.find("growing: true"), 13, "growing: maybe");
  try {
    Overlay::parse(bad, "g.yaml");
    FAIL() << "growing: maybe was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "g.yaml");
    EXPECT_EQ(e.where().field, "growing");
    EXPECT_GT(e.where().line, 0u);
  }
  std::string no_half = yaml;
  const std::size_t half_at = no_half.find("    half:");
  no_half.erase(half_at, no_half.find('\n', half_at) - half_at + 1);
  EXPECT_THROW(Overlay::parse(no_half, "g.yaml"), InputError);
}

bool has_growing(const CandidateSet& cs, int axis) {
  for (const Term& t : cs.fixed)
    if (t.kind == TermKind::reversal && t.axis == axis && t.degree == 1) return true;
  return false;
}

// A laser line along X (targets 0..400 mm every 40 mm), `runs` runs: each
// forward over every target, then back over the targets from `back_from`
// down, 5 s per target; d_x(x, v, t) + N(0, σ²).
template <class Deviation>
Problem x_line(int runs, int back_from, double sigma, std::uint64_t seed, Deviation d) {
  Problem pb;
  std::vector<double> y;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  double t = 0.0;
  auto read = [&](int k, int way) {
    PointContext pc;
    pc.p = pc.s = Eigen::Vector3d(40.0 * k, 100.0, 0.0);
    pc.dir = {way, 1, 1};
    pc.t = t;
    t += 5.0;
    pc.set = "line";
    test::add_reading(pb, y, pc, Eigen::Vector3d::UnitX(), d(pc) + noise(rng));
  };
  for (int run = 0; run < runs; ++run) {
    for (int k = 0; k <= 10; ++k) read(k, 1);
    for (int k = back_from; k >= 0; --k) read(k, -1);
  }
  test::finish_problem(pb, y, "line", {true, false, false}, Eigen::Vector3d(0.0, 100.0, 0.0),
                       Eigen::Vector3d(400.0, 100.0, 0.0));
  pb.var_lo[3] = 0.0;
  pb.var_hi[3] = t;
  return pb;
}

TEST(DiagnoseGrowingReversal, ACandidateOnlyWhereItsGrowthIsNotAScale) {
  auto zero = [](const PointContext&) { return 0.0; };
  // Both ways over the whole travel: a candidate.
  EXPECT_TRUE(has_growing(build_candidates(x_line(1, 10, 0.0, 1, zero), CandidateOptions{}), 0));
  EXPECT_TRUE(has_growing(build_candidates(test::two_laser_lines(true), CandidateOptions{}), 1));
  // Back over the last two targets only: sign(v)·x is nearly x there.
  const Problem one_way = x_line(1, 1, 0.0, 1, zero);
  const CandidateSet cs = build_candidates(one_way, CandidateOptions{});
  EXPECT_FALSE(has_growing(cs, 0));
  bool plain = false;
  for (const Term& t : cs.fixed) plain = plain || (t.kind == TermKind::reversal && t.degree == 0);
  EXPECT_TRUE(plain);  // the jump itself is still seen
  CandidateOptions any_correlation;
  any_correlation.max_growth_correlation = 1.01;
  EXPECT_TRUE(has_growing(build_candidates(one_way, any_correlation), 0));  // the gate left it out
  CandidateOptions off;
  off.growing_reversal = false;
  EXPECT_FALSE(has_growing(build_candidates(x_line(1, 10, 0.0, 1, zero), off), 0));
}

// Five runs there and back, noise 0.3 µm: a 4 µm jump that grows by
// `growth` µm from the middle to the end of the travel.
SelectionResult select_line(double growth, std::uint64_t seed) {
  const Problem pb = x_line(5, 10, 0.3, seed, [&](const PointContext& pc) {
    return 0.5 * pc.dir[0] * (4.0 + growth * (pc.s.x() - 200.0) / 200.0);
  });
  return select_effects(pb, build_candidates(pb, CandidateOptions{}), SelectionOptions{});
}

const SelectedTerm* reversal_of(const SelectionResult& r) {
  for (const SelectedTerm& st : r.terms)
    if (st.term.kind == TermKind::reversal) return &st;
  return nullptr;
}

TEST(DiagnoseGrowingReversal, NamedWithItsGrowthOnlyWhereTheDataHoldOne) {
  int grown = 0, plain_named_plain = 0;
  constexpr int kSeeds = 10;
  for (int seed = 0; seed < kSeeds; ++seed) {
    const SelectionResult with = select_line(1.5, 100 + static_cast<std::uint64_t>(seed));
    const SelectedTerm* g = reversal_of(with);
    ASSERT_NE(g, nullptr);
    EXPECT_TRUE(g->ambiguous_with.empty()) << g->ambiguous_with.front();
    if (g->term.degree == 1) {
      ++grown;
      ASSERT_EQ(g->term.coef.size(), 2u);
      ASSERT_EQ(g->term.stderr_.size(), 2u);
      EXPECT_GT(g->term.stderr_[1], 0.0);
      EXPECT_NEAR(g->term.coef[0], 4.0, 4.0 * g->term.stderr_[0]);
      EXPECT_NEAR(g->term.coef[1], 1.5, 4.0 * g->term.stderr_[1]);
    }
    const SelectionResult without = select_line(0.0, 200 + static_cast<std::uint64_t>(seed));
    const SelectedTerm* p = reversal_of(without);
    ASSERT_NE(p, nullptr);
    plain_named_plain += p->term.degree == 0 ? 1 : 0;
    EXPECT_NEAR(p->term.coef[0], 4.0, 0.3);
  }
  EXPECT_EQ(grown, kSeeds);
  EXPECT_GE(plain_named_plain, kSeeds - 1);  // a growth found in noise: at most once
}

}  // namespace
}  // namespace abbe::diagnose
