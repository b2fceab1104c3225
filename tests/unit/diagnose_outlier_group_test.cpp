// Outliers and structure (issue 16): a coherent group of points that a
// catalogue effect explains is not gross error. A design that runs an axis
// one way except for one run the other way puts that run a whole reversal
// off; flagged as outliers after the datum alone, the reversal could not
// be seen in the rest. With OutlierOptions::group_check the selection is
// run once more with every point, and the flagging restarts from what that
// model leaves: the reversal is named and nothing is flagged. Without the
// check the run is left out and the reversal is lost.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "abbe/diagnose/diagnosis.hpp"
#include "diagnose_test_problem.hpp"

namespace abbe::diagnose {
namespace {

// 21 rows of 51 points along X (10 mm apart) at y = 0, 20, …, 400 mm; every
// row runs +X but the middle one, which runs −X; dx measured, no time,
// noise 0.5 µm, X jumps by `reversal` µm between the two directions.
Problem one_way_rows(double reversal, std::uint64_t seed) {
  Problem pb;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.5);
  std::vector<double> y;
  for (int row = 0; row < 21; ++row)
    for (int i = 0; i <= 50; ++i) {
      PointContext pc;
      const int dir = row == 10 ? -1 : 1;
      const double x = dir > 0 ? 10.0 * i : 500.0 - 10.0 * i;
      pc.p = pc.s = Eigen::Vector3d(-700.0 + x, -450.0 + 20.0 * row, -230.0);
      pc.dir = {dir, 1, 0};
      pc.set = "rows";
      pb.obs.push_back({static_cast<std::uint32_t>(pb.points.size()), Eigen::Vector3d::UnitX()});
      y.push_back(0.5 * reversal * dir + noise(rng));
      pb.points.push_back(pc);
      pb.lines.push_back(pb.points.size() + 1);
    }
  const Eigen::Vector3d lo(-700.0, -450.0, -230.0), hi(-200.0, -50.0, -230.0);
  test::finish_problem(pb, y, "rows", {true, false, false}, lo, hi);
  return pb;
}

bool names_reversal_x(const Diagnosis& d, double value) {
  for (const SelectedTerm& st : d.effects)
    if (st.term.kind == TermKind::reversal && st.term.axis == 0 && st.term.direction == 0 &&
        st.significant && !st.term.coef.empty() && std::abs(st.term.coef[0] - value) < 0.5)
      return true;
  return false;
}

TEST(DiagnoseOutlierGroup, AReversalRunIsStructureNotOutliers) {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const Problem pb = one_way_rows(6.0, seed);
    DiagnoseOptions o;
    const Diagnosis with = diagnose_problem(pb, o);
    EXPECT_TRUE(with.outliers.empty()) << "seed " << seed << ": " << with.outliers.size();
    EXPECT_TRUE(names_reversal_x(with, 6.0)) << "seed " << seed;
    // Without the check the run the other way is flagged and the reversal lost.
    o.outliers.group_check = false;
    const Diagnosis without = diagnose_problem(pb, o);
    EXPECT_EQ(without.outliers.size(), 51u) << "seed " << seed;
    EXPECT_FALSE(names_reversal_x(without, 6.0)) << "seed " << seed;
  }
}

TEST(DiagnoseOutlierGroup, WhereTheFitWithEveryPointLeavesNoneItIsTheOnlySelection) {
  // The run the other way lies beyond the threshold of the datum alone;
  // the model selected with every point leaves no point beyond its own.
  // The flagging from the datum alone would end at that selection (the
  // check keeps the result that leaves out fewer points), so it is the
  // result at once: one selection with the caller's options (counted by
  // its first step), and the same effects as without outlier flagging.
  const Problem pb = one_way_rows(6.0, 2);
  DiagnoseOptions o;
  int selections = 0;
  o.selection.on_step = [&](int step) { selections += step == 0 ? 1 : 0; };
  const Diagnosis d = diagnose_problem(pb, o);
  EXPECT_EQ(selections, 1);
  EXPECT_TRUE(d.outliers.empty());
  EXPECT_TRUE(names_reversal_x(d, 6.0));
  DiagnoseOptions plain;
  plain.outliers.enabled = false;
  const Diagnosis p = diagnose_problem(pb, plain);
  ASSERT_EQ(d.effects.size(), p.effects.size());
  for (std::size_t i = 0; i < d.effects.size(); ++i) {
    EXPECT_EQ(d.effects[i].term.label(), p.effects[i].term.label());
    EXPECT_EQ(d.effects[i].term.coef, p.effects[i].term.coef);
  }
  EXPECT_GT(d.outlier_threshold_um, 0.0);
}

TEST(DiagnoseOutlierGroup, ScatteredGrossErrorsAreStillFlagged) {
  // The same rows without a reversal, 2 % of the points 20–50 µm off: the
  // check selects with them, but no catalogue effect explains scattered
  // gross errors, so the same points stay flagged.
  Problem pb = one_way_rows(0.0, 4);
  std::mt19937_64 rng(11);
  std::vector<std::size_t> bad;
  while (bad.size() < 11) {
    const std::size_t p = static_cast<std::size_t>(rng() % pb.points.size());
    if (std::find(bad.begin(), bad.end(), p) == bad.end()) bad.push_back(p);
  }
  for (std::size_t k = 0; k < bad.size(); ++k)
    pb.y[static_cast<Eigen::Index>(bad[k])] +=
        (k % 2 ? -1.0 : 1.0) * (20.0 + 3.0 * static_cast<double>(k));
  const Diagnosis d = diagnose_problem(pb, DiagnoseOptions{});
  EXPECT_EQ(d.outliers.size(), bad.size());
  for (const Outlier& out : d.outliers)
    EXPECT_NE(std::find(bad.begin(), bad.end(), out.point), bad.end());
}

}  // namespace
}  // namespace abbe::diagnose
