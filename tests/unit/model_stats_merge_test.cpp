// ModelSet keeps the statistics of the cutting and the rapid points and
// merges them for all points (pipeline::merged) instead of a third running
// statistic per point: the merged statistic must be exactly the one a single
// running statistic over all points in order gives — counts, per-axis
// maxima, the largest |e| and the line of its first point (ties between the
// groups included), and the sum of |e|² in point order.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "abbe/machine/machine.hpp"
#include "abbe/model/error_model.hpp"
#include "abbe/model/model_kind.hpp"
#include "abbe/pipeline/model_set.hpp"

namespace abbe::pipeline {
namespace {

const std::string kMachine = std::string(ABBE_SOURCE_DIR) + "/machines/sample/machine.yaml";

void expect_same(const ModelStats& a, const ModelStats& b) {
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(a.max_abs_um, b.max_abs_um);
  EXPECT_EQ(a.max_um, b.max_um);
  EXPECT_EQ(a.max_line, b.max_line);
}

// Deviations drawn from a few values, so that equal maxima fall in both groups.
struct Stream {
  std::vector<Eigen::Vector3d> e;
  std::vector<bool> rapid;
  std::vector<std::size_t> line;
};

Stream stream(std::uint32_t seed, std::size_t n, bool zeros) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> v(-3, 3), coin(0, 1), step(0, 2);
  Stream s;
  std::size_t line = 1;
  for (std::size_t i = 0; i < n; ++i) {
    s.e.push_back(zeros ? Eigen::Vector3d::Zero()
                        : Eigen::Vector3d(static_cast<double>(v(rng)), static_cast<double>(v(rng)),
                                          static_cast<double>(v(rng))));
    s.rapid.push_back(coin(rng) == 1);
    line += static_cast<std::size_t>(step(rng));
    s.line.push_back(line);
  }
  return s;
}

TEST(ModelStatsMerge, MergedGroupsAreTheRunningStatisticOfAllPoints) {
  for (std::uint32_t seed = 1; seed <= 50; ++seed)
    for (bool zeros : {false, true}) {
      const Stream s = stream(seed, 1 + seed * 7, zeros);
      ModelStats all, cutting, rapid;
      for (std::size_t i = 0; i < s.e.size(); ++i) {
        const double d = s.e[i].norm();
        all.add(s.e[i], d, s.line[i], i);
        (s.rapid[i] ? rapid : cutting).add(s.e[i], d, s.line[i], i);
      }
      const ModelStats m = merged(cutting, rapid);
      expect_same(m, all);
      expect_same(merged(rapid, cutting), all);
      EXPECT_EQ(m.max_point, all.max_point);
      EXPECT_NEAR(m.sum_d2, all.sum_d2, 1e-12 * all.sum_d2);
    }
}

TEST(ModelStatsMerge, TieGoesToTheEarlierPointOfEitherGroup) {
  ModelStats cutting, rapid;
  const Eigen::Vector3d big(0.0, 3.0, 4.0), small(1.0, 0.0, 0.0);
  rapid.add(small, 1.0, 10, 0);
  rapid.add(big, 5.0, 11, 1);    // the first largest |e|: line 11
  cutting.add(big, 5.0, 12, 2);  // as large, later
  cutting.add(small, 1.0, 13, 3);
  EXPECT_EQ(merged(cutting, rapid).max_line, 11u);
  EXPECT_EQ(merged(rapid, cutting).max_line, 11u);
  EXPECT_EQ(merged(cutting, rapid).points, 4u);
  EXPECT_EQ(merged(cutting, ModelStats{}).max_line, 12u);
  EXPECT_EQ(merged(ModelStats{}, rapid).max_line, 11u);
}

TEST(ModelStatsMerge, ModelSetStatisticsAreThoseOfEveryPointInOrder) {
  const machine::Machine m = machine::Machine::load(kMachine);
  const std::vector<model::ModelKind> kinds = {model::ModelKind::htm, model::ModelKind::ae_arm,
                                               model::ModelKind::dual};
  ModelSet set(m, kinds);
  std::vector<ModelStats> all(kinds.size());
  for (int i = 0; i < 300; ++i) {
    model::EvalPoint p;
    p.p = Eigen::Vector3d(-20.0 - 2.3 * i, -10.0 - 1.15 * (i % 97), -30.0 - 0.9 * (i % 17));
    p.tool_length = 100.0;
    p.dir = {static_cast<std::int8_t>(i % 2 ? 1 : -1), 1, static_cast<std::int8_t>(i % 3 - 1)};
    const std::size_t line = 1 + static_cast<std::size_t>(i) / 3;
    set.evaluate(p, "t.ngc", line, i % 5 < 2);
    for (std::size_t k = 0; k < kinds.size(); ++k)
      all[k].add(set.deviations()[k].e_um, set.norms_um()[k], line);
  }
  const std::vector<ModelStats> merged_all = set.stats();
  ASSERT_EQ(merged_all.size(), kinds.size());
  for (std::size_t k = 0; k < kinds.size(); ++k) {
    expect_same(merged_all[k], all[k]);
    EXPECT_EQ(merged_all[k].sum_d2, all[k].sum_d2);  // the same sum, in the same order
    EXPECT_EQ(merged_all[k].points, set.cutting_stats()[k].points + set.rapid_stats()[k].points);
    EXPECT_GT(set.rapid_stats()[k].points, 0u);
  }
}

}  // namespace
}  // namespace abbe::pipeline
