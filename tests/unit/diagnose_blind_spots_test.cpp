// What the design cannot test at all (blind_spots.hpp): hand-made layouts
// with known blind spots — irregular points measured in every direction
// with time and both approach directions (none), a plate (no dz, no time,
// no approach direction, one z), two laser lines (each direction measured
// where the other axis stands still) and a regular grid (cycles alias).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "abbe/diagnose/blind_spots.hpp"
#include "diagnose_test_problem.hpp"

namespace abbe::diagnose {
namespace {

struct Layout {
  bool dz = true, time = true, directions = true, regular = false, flat = false;
};

// 200 points in a 600 × 400 × 300 mm box, dx dy (dz) read at each.
Problem make_layout(const Layout& l) {
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Problem pb;
  std::vector<double> y;
  for (int k = 0; k < 200; ++k) {
    PointContext pc;
    if (l.regular) {
      pc.p = {50.0 * (k % 10), 50.0 * ((k / 10) % 5), 100.0 * (k / 50)};
    } else {
      pc.p = {600.0 * u(rng), 400.0 * u(rng), 300.0 * u(rng)};
    }
    if (l.flat) pc.p.z() = 0.0;
    pc.s = pc.p;
    pc.t = l.time ? 5.0 * k : 0.0;
    if (l.directions) pc.dir = {k % 2 ? 1 : -1, k % 3 ? 1 : -1, k % 5 ? 1 : -1};
    pc.set = "a";
    for (int i = 0; i < (l.dz ? 3 : 2); ++i)
      test::add_reading(pb, y, pc, Eigen::Vector3d::Unit(i), 0.0);
  }
  test::finish_problem(pb, y, "a", {true, true, l.dz}, {0.0, 0.0, 0.0}, {600.0, 400.0, 300.0});
  return pb;
}

std::vector<std::string> whats(const Problem& pb) {
  std::vector<std::string> out;
  for (const BlindSpot& b : blind_spots(pb, DesignAmbiguityOptions{}, 4.0, 100.0)) {
    EXPECT_FALSE(b.reason.empty()) << b.what;
    EXPECT_FALSE(b.measure.empty()) << b.what;
    out.push_back(b.what);
  }
  return out;
}

bool has(const std::vector<std::string>& v, const std::string& start) {
  return std::any_of(v.begin(), v.end(),
                     [&](const std::string& s) { return s.rfind(start, 0) == 0; });
}

TEST(DiagnoseBlindSpots, ScatteredPointsInEveryDirectionSeeTheWholeCatalogue) {
  EXPECT_TRUE(whats(make_layout({})).empty());
}

TEST(DiagnoseBlindSpots, APlateHasNoZNoTimeAndNoReversal) {
  Layout l;
  l.dz = false;
  l.time = false;
  l.directions = false;
  l.flat = true;
  const auto w = whats(make_layout(l));
  EXPECT_TRUE(has(w, "every effect in Z (dz)"));
  EXPECT_TRUE(has(w, "a drift in time"));
  EXPECT_TRUE(has(w, "a reversal of X"));
  EXPECT_TRUE(has(w, "a reversal of Y"));
  EXPECT_TRUE(has(w, "every effect that varies with z"));
  EXPECT_FALSE(has(w, "a reversal of Z"));  // at one z, one way: the datum's constant
  EXPECT_EQ(w.size(), 5u);
}

TEST(DiagnoseBlindSpots, ALineSeesItsDirectionAlongItsAxisOnly) {
  // d_x along X at y = 100, d_y along Y at x = 200, there and back, z = 0.
  const Problem pb = test::two_laser_lines(true);
  const auto w = whats(pb);
  EXPECT_TRUE(has(w, "dx as a function of y"));
  EXPECT_TRUE(has(w, "dy as a function of x"));
  EXPECT_TRUE(has(w, "every effect in Z (dz)"));
  EXPECT_TRUE(has(w, "every effect that varies with z"));
  EXPECT_FALSE(has(w, "a drift in time"));
  EXPECT_FALSE(has(w, "a reversal of X"));
  // Targets 40 mm apart on 11 levels: the cycles below 80 mm alias. On 11
  // levels a cycle's kind may still be named (its period not), and the
  // reason says so; not on 10 (DesignAmbiguityOptions::period_only_min_levels).
  EXPECT_TRUE(has(w, "a cycle of X shorter than 80 mm"));
  for (const std::size_t min_levels : {11u, 12u}) {
    DesignAmbiguityOptions o;
    o.period_only_min_levels = min_levels;
    for (const BlindSpot& b : blind_spots(pb, o, 4.0, 100.0)) {
      if (b.what.rfind("a cycle of X", 0) != 0) continue;
      const bool says =
          b.reason.find("a cycle's kind is still named, its period not") != std::string::npos;
      EXPECT_EQ(says, min_levels == 11u) << b.reason;
    }
  }
}

TEST(DiagnoseBlindSpots, RegularLevelsCannotSeeTheCyclesTheyAlias) {
  Layout l;
  l.regular = true;
  const auto w = whats(make_layout(l));
  // X on 10 levels 50 mm apart and Y on 5 (cycles below 100 mm), Z on 4
  // levels 100 mm apart (every period of the catalogue, up to 100 mm).
  EXPECT_TRUE(has(w, "a cycle of X shorter than 100 mm"));
  EXPECT_TRUE(has(w, "a cycle of Y shorter than 100 mm"));
  EXPECT_TRUE(has(w, "a cycle of Z (a pitch error; every period of the catalogue"));
  EXPECT_EQ(w.size(), 3u);
}

// A short travel (a 50 mm ballbar circle: X and Y span 100 mm): no cycle
// longer than half the span, said per axis; an 800 mm line none.
TEST(DiagnoseBlindSpots, AShortTravelCannotSeeItsLongerPeriods) {
  const auto w = whats(test::sine_line(0.0, 100.0, 200, 20.0, 1.0, 0.0, 0.1, 1, 2));
  EXPECT_TRUE(has(w, "a cycle of X longer than 50 mm"));
  const auto far = whats(test::sine_line(0.0, 800.0, 200, 20.0, 1.0, 0.0, 0.1, 1, 2));
  EXPECT_FALSE(has(far, "a cycle of X longer"));
  // The share as an option: with 1.0 the 100 mm line holds every period.
  bool said = false;
  for (const BlindSpot& b : blind_spots(test::sine_line(0.0, 100.0, 200, 20.0, 1.0, 0.0, 0.1, 1, 2),
                                        DesignAmbiguityOptions{}, 4.0, 100.0, 1.0))
    said = said || b.what.rfind("a cycle of X longer", 0) == 0;
  EXPECT_FALSE(said);
}

}  // namespace
}  // namespace abbe::diagnose
