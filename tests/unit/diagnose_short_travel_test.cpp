// Cycles over a short travel (a 50 mm ballbar circle spans 100 mm of X and
// Y): the catalogue scans periods only up to half the measured travel
// (CandidateOptions::max_period_span_share), a refined period stays within
// its family's frequencies (parameter_scan.hpp, FrequencyRange), a second
// cycle of one axis is not scanned within the resolution 1/span of a
// chosen one (SelectionOptions::resolve_chosen_cycles), and the chosen
// cycles' periods are refined once more beside each other in the final
// fit (SelectionOptions::refine_periods, chosen_periods.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "abbe/diagnose/candidates.hpp"
#include "abbe/diagnose/selection.hpp"
#include "diagnose_test_problem.hpp"
#include "src/diagnose/parameter_scan.hpp"

namespace abbe::diagnose {
namespace {

using selection::Mat;
using selection::Vec;
constexpr double kTwoPi = 6.283185307179586;

// The longest period of the cyclic family of X→X, 0 when there is none.
double longest_period(const CandidateSet& cs) {
  for (const ScanFamily& f : cs.scanned)
    if (f.base.kind == TermKind::cyclic && f.base.axis == 0 && f.base.direction == 0)
      return std::max(f.grid.front(), f.grid.back());
  return 0.0;
}

TEST(DiagnoseShortTravel, ThePeriodsScannedAreAtMostHalfTheTravel) {
  const CandidateOptions o;
  // 100 mm of X: periods up to 50 mm (two on the travel).
  const double at_100 = longest_period(
      build_candidates(test::sine_line(0.0, 100.0, 200, 20.0, 1.0, 0.0, 0.1, 1, 2), o));
  EXPECT_LE(at_100, 50.0 * (1.0 + 1e-9));
  EXPECT_GT(at_100, 45.0);
  // 800 mm: the catalogue's own limit, 100 mm.
  const double at_800 = longest_period(
      build_candidates(test::sine_line(0.0, 800.0, 200, 20.0, 1.0, 0.0, 0.1, 1, 2), o));
  EXPECT_NEAR(at_800, o.max_period_mm, 1e-6);
  // 6 mm: no period of the catalogue (4 mm or more) fits twice: no cycle.
  EXPECT_EQ(
      longest_period(build_candidates(test::sine_line(0.0, 6.0, 50, 20.0, 1.0, 0.0, 0.1, 1, 2), o)),
      0.0);
  // The share as an option: 1.0 allows one period on the travel.
  CandidateOptions whole = o;
  whole.max_period_span_share = 1.0;
  EXPECT_GT(longest_period(build_candidates(
                test::sine_line(0.0, 100.0, 200, 20.0, 1.0, 0.0, 0.1, 1, 2), whole)),
            95.0);
}

// A cycle of 70 mm on 100 mm of X, its refinement started at the family's
// longest period (50 mm): within the family's frequencies it stays at 50 mm
// or shorter; without the range it walks out towards 70 mm.
TEST(DiagnoseShortTravel, ARefinedPeriodStaysInItsFamilysRange) {
  const Problem pb = test::sine_line(0.0, 100.0, 400, 70.0, 3.0, 0.3, 0.05, 3, 4);
  const auto n = pb.y.size();
  const Mat Q = Mat::Constant(n, 1, 1.0 / std::sqrt(static_cast<double>(n)));
  const Vec r = pb.y - Q * (Q.transpose() * pb.y);
  auto start = [&] {
    Term t;
    t.kind = TermKind::cyclic;
    t.axis = 0;
    t.direction = 0;
    t.period_mm = 50.0;
    selection::Cached c{t, term_columns(pb, t), Mat(), Mat(), {}};
    c.CtC = c.C.transpose() * c.C;
    c.QtC = Q.transpose() * c.C;
    return c;
  };
  const double step = 0.25 / 100.0;
  selection::Cached bounded = start();
  selection::refine_period_exactly(pb, Q, r, step, bounded, {1.0 / 50.0, 1.0 / 4.0});
  EXPECT_LE(bounded.term.period_mm, 50.0 * (1.0 + 1e-9));
  selection::Cached free = start();
  selection::refine_period_exactly(pb, Q, r, step, free);
  EXPECT_GT(free.term.period_mm, 55.0);  // the test could fail
}

// A pitch error with its second harmonic over 100 mm of X (a laser line of
// 400 irregular targets; period 37 mm, 3 µm and 1 µm, noise 0.2 µm).
Problem short_pitch_line(std::uint64_t seed) {
  Problem pb;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.2);
  const double period = 36.0 + 2.0 * u(rng), ph1 = kTwoPi * u(rng), ph2 = kTwoPi * u(rng);
  std::vector<double> y;
  for (int k = 0; k < 400; ++k) {
    const double x = 100.0 * u(rng);
    PointContext pc;
    pc.p = pc.s = Eigen::Vector3d(x, 0.0, 0.0);
    pc.dir = {1, 1, 1};
    pc.set = "a";
    test::add_reading(pb, y, pc, Eigen::Vector3d::UnitX(),
                      3.0 * std::sin(kTwoPi * x / period + ph1) +
                          std::sin(2.0 * kTwoPi * x / period + ph2) + noise(rng));
  }
  test::finish_problem(pb, y, "a", {true, false, false}, Eigen::Vector3d::Zero(),
                       Eigen::Vector3d(100.0, 0.0, 0.0));
  pb.travel_mid = Eigen::Vector3d(50.0, 0.0, 0.0);
  return pb;
}

// What the selection names beside the datum: the number of cycles and of
// other named terms.
struct Named {
  int cycles = 0, others = 0;
  std::string text;
};
Named named(const SelectionResult& r) {
  Named n;
  for (const SelectedTerm& st : r.terms) {
    if (st.term.kind == TermKind::setup_offset || st.term.kind == TermKind::setup_rotation ||
        st.term.kind == TermKind::unexplained)
      continue;
    (st.term.kind == TermKind::cyclic ? n.cycles : n.others) += 1;
    n.text += " [" + st.term.label() + "]";
  }
  return n;
}

TEST(DiagnoseShortTravel, APitchErrorOnAShortTravelIsItsTwoCycles) {
  int right = 0, right_without = 0;
  const int seeds = 8;
  for (int seed = 1; seed <= seeds; ++seed) {
    const Problem pb = short_pitch_line(static_cast<std::uint64_t>(seed));
    const CandidateSet cs = build_candidates(pb, CandidateOptions{});
    SelectionOptions o;
    const Named with = named(select_effects(pb, cs, o));
    right += with.cycles == 2 && with.others == 0 ? 1 : 0;
    std::cout << "seed " << seed << ":" << with.text;
    o.resolve_chosen_cycles = false;
    o.refine_periods = false;
    const Named without = named(select_effects(pb, cs, o));
    right_without += without.cycles == 2 && without.others == 0 ? 1 : 0;
    std::cout << "; without:" << without.text << "\n";
  }
  EXPECT_EQ(right, seeds);
  EXPECT_LT(right_without, seeds) << "as many without the two rules: no test";
}

}  // namespace
}  // namespace abbe::diagnose
