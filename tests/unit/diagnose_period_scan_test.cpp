// The searched parameters of the selection's scan (parameter_scan.cpp).
// The period of a cycle: the periodogram's grid steps a quarter of
// 1/travel, and the peak between two grid frequencies is refined by a
// parabola (SelectionOptions::refine_period), then the chosen cycle's on
// the exact ΔRSS (exact_period); that case is also run with each alone and
// with neither, to show the test could fail without them. The time
// constant of a drift: the largest projection of the residual on the
// drift's column without its mean per set (each set's offset is datum).
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>
#include <vector>

#include "abbe/diagnose/candidates.hpp"
#include "abbe/diagnose/selection.hpp"
#include "diagnose_test_problem.hpp"
#include "src/diagnose/parameter_scan.hpp"

namespace abbe::diagnose {
namespace {

// A laser line along X over 800 mm (a point every 2.5 mm, dx measured) with
// a ballscrew cycle of 3 µm whose frequency lies half-way between two of
// the scan grid's (the worst case: 1/100 mm + 100.5 steps of 1/3200 mm),
// noise 0.2 µm.
Problem line_with_cycle(std::uint64_t seed, double period_mm) {
  Problem pb;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.2);
  std::uniform_real_distribution<double> phase(0.0, 6.283185307179586);
  const double ph = phase(rng);
  std::vector<double> y;
  const Eigen::Vector3d lo(-900, -250, -200), hi(-100, -250, -200);
  for (int i = 0; i <= 320; ++i) {
    PointContext pc;
    pc.p = pc.s = Eigen::Vector3d(-900.0 + 2.5 * i, -250.0, -200.0);
    pc.set = "line";
    test::add_reading(pb, y, pc, Eigen::Vector3d::UnitX(),
                      3.0 * std::sin(6.283185307179586 * pc.s.x() / period_mm + ph) + noise(rng));
  }
  test::finish_problem(pb, y, "line", {true, false, false}, lo, hi);
  return pb;
}

TEST(DiagnosePeriodScan, APeriodBetweenTheGridsFrequenciesIsRefined) {
  const double f = 1.0 / 100.0 + 100.5 / 3200.0;
  const double period = 1.0 / f;  // 24.15 mm
  int close = 0, off_without = 0;
  const int seeds = 10;
  for (int seed = 1; seed <= seeds; ++seed) {
    const Problem pb = line_with_cycle(static_cast<std::uint64_t>(seed), period);
    const CandidateSet cs = build_candidates(pb, CandidateOptions{});
    auto cycle_error = [&](const SelectionResult& r) {
      for (const SelectedTerm& st : r.terms)
        if (st.term.kind == TermKind::cyclic && st.term.axis == 0 && st.term.direction == 0)
          return std::abs(st.term.period_mm / period - 1.0);
      return 1.0;
    };
    SelectionOptions o;
    const SelectionResult with = select_effects(pb, cs, o);
    const double e = cycle_error(with);
    std::cout << "seed " << seed << ": period off by " << 100.0 * e << " %";
    if (e < 1e-3)
      ++close;
    else
      ADD_FAILURE() << "seed " << seed << ": period off by " << 100.0 * e << " %";
    // The chosen cycle's refinement on the exact ΔRSS (exact_period) alone
    // gets there too from the grid's frequency.
    o.refine_period = false;
    const double e_exact = cycle_error(select_effects(pb, cs, o));
    EXPECT_LT(e_exact, 1e-3) << "seed " << seed << ": the exact refinement alone";
    o.exact_period = false;
    o.refine_periods = false;  // nor the final fit's (chosen_periods.hpp)
    const double e0 = cycle_error(select_effects(pb, cs, o));
    std::cout << "; without either refinement " << 100.0 * e0 << " %\n";
    if (e0 > 2e-3) ++off_without;
  }
  EXPECT_EQ(close, seeds);
  EXPECT_GT(off_without, 0) << "without the refinement the period is as close: no test";
}

TEST(DiagnosePeriodScan, ADriftsTimeConstantIsFoundWhateverEachSetsOffset) {
  // Three sets (test::drift_runs: runs of one line along X, 20 min apart,
  // each with an unknown offset, the datum): dX = 4 µm·(1 − e^(−t/τ)) for
  // τ of the grid; the scan gets the residual after the datum, as the
  // selection does, and must return τ (and no aliases, for a drift). With
  // the column's full norm instead of its norm without each set's mean, the
  // scan returns 300 s for all three (measured by switching that off).
  const std::vector<double> grid = CandidateOptions{}.tau_s;
  for (double tau : {600.0, 1800.0, 3600.0}) {
    const Problem pb = test::drift_runs(tau, 4.0, 0.1, static_cast<std::uint64_t>(tau));
    // The residual after the datum: each set's mean removed.
    Eigen::VectorXd r = pb.y;
    for (int set = 0; set < 3; ++set) {
      auto seg = r.segment(81 * set, 81);
      seg.array() -= seg.mean();
    }
    Eigen::MatrixXd R, W;
    selection::point_sums(pb, r, R, W);
    std::vector<std::size_t> set_of(pb.points.size());
    for (std::size_t p = 0; p < set_of.size(); ++p) set_of[p] = p / 81;
    ScanFamily f;
    f.base = test::make_term(TermKind::thermal_drift, 0, 0);
    f.grid = grid;
    selection::PowerCache power;
    std::vector<double> aliases;
    const Term found =
        selection::scan_parameter(f, {pb, R, W, set_of, 1, 0.9, true}, power, aliases);
    EXPECT_EQ(found.tau_s, tau);
    EXPECT_TRUE(aliases.empty());
  }
}

}  // namespace
}  // namespace abbe::diagnose
