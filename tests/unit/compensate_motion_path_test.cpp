// MotionPath: the closest point of lines, arcs and helices (analytic, with
// Newton refinement) against a dense search; reversal points of arcs and
// the direction signs on either side of them.
#include <gtest/gtest.h>

#include <random>

#include "abbe/compensate/motion_path.hpp"

namespace abbe::compensate {
namespace {

gcode::Motion random_arc(std::mt19937& g, int i) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  gcode::Motion m;
  m.kind = gcode::MotionKind::arc;
  m.plane = static_cast<gcode::Plane>(i % 3);
  const int turns = 1 + (i % 7 == 0 ? (i / 7) % 3 : 0);
  m.rotation = (u(g) > 0 ? 1 : -1) * turns;
  const Eigen::Vector3d c(100 * u(g), 100 * u(g), 100 * u(g));
  const double r = 30.0 * std::abs(u(g)) + 0.5, t0 = 4.0 * u(g), t1 = 4.0 * u(g);
  const double r1 = r * (1.0 + 1e-5 * u(g));  // an end slightly off the circle
  const auto ax = plane_axes(m.plane);
  m.center = m.start = m.end = c;
  m.start[ax[0]] += r * std::cos(t0);
  m.start[ax[1]] += r * std::sin(t0);
  m.end[ax[0]] += r1 * std::cos(t1);
  m.end[ax[1]] += r1 * std::sin(t1);
  if (i % 2) m.end[ax[2]] += 20.0 * u(g);  // helix
  return m;
}

TEST(MotionPath, ClosestPointOfArcsAndHelicesMatchesADenseSearch) {
  std::mt19937 g(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0), t(0.0, 1.0);
  for (int i = 0; i < 100; ++i) {
    const MotionPath p(random_arc(g, i));
    // Points near the curve (what compensate and verify ask for).
    const Eigen::Vector3d q = p.at(t(g)) + 0.05 * Eigen::Vector3d(u(g), u(g), u(g));
    double dense = 1e9;
    constexpr int kN = 20000;
    for (int k = 0; k <= kN; ++k) dense = std::min(dense, (p.at(double(k) / kN) - q).norm());
    const double d = p.distance(q);
    EXPECT_LE(d, dense + 1e-9) << i;
    EXPECT_GE(d, dense - 1e-3) << i;  // the dense search is an upper bound
  }
}

// The quick distance of points near an arc of at most one turn agrees with
// the exact one.
TEST(MotionPath, DistanceNearAnArc) {
  std::mt19937 g(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0), t(0.0, 1.0);
  for (int i = 0; i < 2000; ++i) {
    gcode::Motion m = random_arc(g, i);
    m.rotation = m.rotation > 0 ? 1 : -1;
    const MotionPath p(m);
    const Eigen::Vector3d q = p.at(t(g)) + 0.002 * Eigen::Vector3d(u(g), u(g), u(g));
    EXPECT_NEAR(p.distance_near(q), p.distance(q), 1e-7) << i;
  }
}

TEST(MotionPath, ClosestPointOfALine) {
  gcode::Motion m;
  m.kind = gcode::MotionKind::linear;
  m.start = {0, 0, 0};
  m.end = {10, 0, 0};
  const MotionPath p(m);
  EXPECT_DOUBLE_EQ(p.closest({4, 3, 0}), 0.4);
  EXPECT_DOUBLE_EQ(p.closest({-4, 3, 0}), 0.0);
  EXPECT_DOUBLE_EQ(p.distance({12, 0, 0}), 2.0);
}

// A counter-clockwise XY circle from angle 0: Y reverses at a quarter and
// three quarters, X at a half; the signs just before and after.
TEST(MotionPath, ReversalsAndTheirDirections) {
  gcode::Motion m;
  m.kind = gcode::MotionKind::arc;
  m.plane = gcode::Plane::xy;
  m.rotation = 1;
  m.center = {0, 0, 0};
  m.start = m.end = {10, 0, 0};
  const MotionPath p(m);
  std::vector<double> r;
  p.for_each_reversal(0.0, 1.0, [&](double t) { r.push_back(t); });
  ASSERT_EQ(r.size(), 3u);
  EXPECT_NEAR(r[0], 0.25, 1e-12);
  EXPECT_NEAR(r[1], 0.5, 1e-12);
  EXPECT_NEAR(r[2], 0.75, 1e-12);
  EXPECT_EQ(p.in_plane_direction(0, 0.2), -1);  // X decreasing
  EXPECT_EQ(p.in_plane_direction(1, 0.2), 1);   // Y increasing
  EXPECT_EQ(p.in_plane_direction(0, 0.3), -1);
  EXPECT_EQ(p.in_plane_direction(1, 0.25 + 1e-6), -1);
  EXPECT_EQ(p.in_plane_direction(1, 0.25), 1);  // at the reversal: the sign before
  // Reversals within kNearReversal of an end count as at the end.
  EXPECT_NEAR(p.near_lo(kNearReversal), kNearReversal / p.length(), 1e-15);
  EXPECT_NEAR(p.near_hi(kNearReversal), 1.0 - kNearReversal / p.length(), 1e-15);
}

}  // namespace
}  // namespace abbe::compensate
