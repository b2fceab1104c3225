// Approach directions from the order of the points
// (io/approach_directions.hpp): hand-made walks with known signs.
#include "abbe/io/approach_directions.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <vector>

namespace abbe::io {
namespace {

MeasuredRow row(double x, double y, double z, double t = 0.0, const char* set = "a") {
  MeasuredRow r;
  r.p = {x, y, z};
  r.t = t;
  r.set = set;
  r.d = {0.0, 0.0, 0.0};
  return r;
}

std::array<std::int8_t, 3> v(const MeasuredRow& r) { return r.v; }
using V = std::array<std::int8_t, 3>;

TEST(ApproachDirections, ASerpentineGetsTheSignOfEachAxissLastMove) {
  MeasuredData d;
  // Row 1 along +x, a step in +y, row 2 along −x, a step down in z.
  for (double x : {0.0, 50.0, 100.0}) d.rows.push_back(row(x, 0.0, 10.0));
  for (double x : {100.0, 50.0, 0.0}) d.rows.push_back(row(x, 40.0, 10.0));
  d.rows.push_back(row(0.0, 40.0, 0.0));
  const std::vector<int> filled = infer_approach_directions(d);
  EXPECT_EQ(filled, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(v(d.rows[0]), (V{0, 0, 0}));  // nothing moved yet
  EXPECT_EQ(v(d.rows[2]), (V{1, 0, 0}));
  EXPECT_EQ(v(d.rows[3]), (V{1, 1, 0}));  // reached by a move in y: x keeps +
  EXPECT_EQ(v(d.rows[4]), (V{-1, 1, 0}));
  EXPECT_EQ(v(d.rows[6]), (V{-1, 1, -1}));
}

TEST(ApproachDirections, TimeOrdersTheWalkAndEachSetStartsAgain) {
  MeasuredData d;
  d.rows.push_back(row(100.0, 0.0, 0.0, 20.0));
  d.rows.push_back(row(0.0, 0.0, 0.0, 0.0));
  d.rows.push_back(row(50.0, 0.0, 0.0, 10.0));
  d.rows.push_back(row(40.0, 0.0, 0.0, 30.0, "b"));  // another set: its first point
  d.rows.push_back(row(20.0, 0.0, 0.0, 40.0, "b"));
  const std::vector<int> filled = infer_approach_directions(d);
  EXPECT_EQ(filled, (std::vector<int>{0}));  // y and z never move
  EXPECT_EQ(d.rows[1].v[0], 0);
  EXPECT_EQ(d.rows[2].v[0], 1);
  EXPECT_EQ(d.rows[0].v[0], 1);
  EXPECT_EQ(d.rows[3].v[0], 0);
  EXPECT_EQ(d.rows[4].v[0], -1);
}

TEST(ApproachDirections, AnAxisTheFileGivesKeepsItsValues) {
  MeasuredData d;
  for (double x : {0.0, 50.0, 100.0}) d.rows.push_back(row(x, x, 0.0));
  d.rows[1].v[0] = -1;  // the file's own X direction (e.g. an overrun approach)
  const std::vector<int> filled = infer_approach_directions(d);
  EXPECT_EQ(filled, (std::vector<int>{1}));
  EXPECT_EQ(d.rows[0].v[0], 0);
  EXPECT_EQ(d.rows[1].v[0], -1);
  EXPECT_EQ(d.rows[2].v[0], 0);
  EXPECT_EQ(d.rows[2].v[1], 1);
}

TEST(ApproachDirections, MovesBelowTheThresholdAreNoMotion) {
  MeasuredData d;
  d.rows.push_back(row(0.0, 0.0, 0.0));
  d.rows.push_back(row(10.0, 0.0, 0.0));
  d.rows.push_back(row(10.0 - 5e-4, 0.0, 0.0));  // 0.5 µm back: a rounding, not a move
  infer_approach_directions(d);
  EXPECT_EQ(d.rows[2].v[0], 1);
}

}  // namespace
}  // namespace abbe::io
