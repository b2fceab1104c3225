// The period of a cycle found by the selection's scan (parameter_scan.cpp):
// the periodogram's grid steps a quarter of 1/travel, and the peak between
// two grid frequencies is refined by a parabola (SelectionOptions::
// refine_period). Each case is also run without the refinement, to show the
// test could fail without it.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>
#include <vector>

#include "abbe/diagnose/candidates.hpp"
#include "abbe/diagnose/selection.hpp"
#include "diagnose_test_problem.hpp"

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
    pb.obs.push_back({static_cast<std::uint32_t>(pb.points.size()), Eigen::Vector3d::UnitX()});
    y.push_back(3.0 * std::sin(6.283185307179586 * pc.s.x() / period_mm + ph) + noise(rng));
    pb.points.push_back(pc);
    pb.lines.push_back(pb.points.size() + 1);
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
    o.refine_period = false;
    const double e0 = cycle_error(select_effects(pb, cs, o));
    std::cout << "; without the refinement " << 100.0 * e0 << " %\n";
    if (e0 > 2e-3) ++off_without;
  }
  EXPECT_EQ(close, seeds);
  EXPECT_GT(off_without, 0) << "without the refinement the period is as close: no test";
}

}  // namespace
}  // namespace abbe::diagnose
