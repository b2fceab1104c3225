// Fragmenter: step bound, exact ends, arcs on their circle (all planes),
// helices with extra turns, direction signs and time estimates.
#include "abbe/path/fragmenter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "abbe/path/arc_span.hpp"

namespace abbe::path {
namespace {

using Eigen::Vector3d;
using gcode::Motion;
using gcode::MotionKind;
using gcode::Plane;

constexpr double kPi = 3.14159265358979323846;

Motion line(const Vector3d& a, const Vector3d& b, double feed = 600.0, std::size_t src = 1) {
  Motion m;
  m.kind = feed > 0.0 ? MotionKind::linear : MotionKind::rapid;
  m.start = a;
  m.end = b;
  m.feed = feed;
  m.line = src;
  m.tool_length = 200.0;
  return m;
}

Motion arc(const Vector3d& a, const Vector3d& b, const Vector3d& c, int rotation,
           Plane plane = Plane::xy, double feed = 600.0) {
  Motion m;
  m.kind = MotionKind::arc;
  m.start = a;
  m.end = b;
  m.center = c;
  m.rotation = rotation;
  m.plane = plane;
  m.feed = feed;
  return m;
}

std::vector<PathPoint> run(const std::vector<Motion>& motions, FragmentOptions options = {}) {
  Fragmenter fragmenter(options);
  std::vector<PathPoint> out;
  for (const auto& m : motions) fragmenter.add(m, [&](const PathPoint& p) { out.push_back(p); });
  return out;
}

double max_gap(const std::vector<PathPoint>& pts) {
  double gap = 0.0;
  for (std::size_t i = 1; i < pts.size(); ++i)
    gap = std::max(gap, (pts[i].p - pts[i - 1].p).norm());
  return gap;
}

TEST(Fragmenter, LineIsSplitIntoEqualStepsNoLongerThanStep) {
  const Vector3d a(-350.0, -150.0, -280.0), b(-650.0, -150.0, -280.0);
  auto pts = run({line(a, b)});
  ASSERT_EQ(pts.size(), 61u);  // start + 300 mm / 5 mm
  EXPECT_EQ(pts.front().p, a);
  EXPECT_EQ(pts.back().p, b);
  for (std::size_t i = 1; i < pts.size(); ++i)
    EXPECT_NEAR((pts[i].p - pts[i - 1].p).norm(), 5.0, 1e-9);

  // 23 mm at step 5 → 5 equal segments of 4.6 mm.
  auto odd = run({line(Vector3d::Zero(), Vector3d(23.0, 0.0, 0.0))});
  ASSERT_EQ(odd.size(), 6u);
  EXPECT_NEAR(odd[1].p.x(), 4.6, 1e-12);
  EXPECT_LE(max_gap(odd), 5.0);

  FragmentOptions fine;
  fine.step = 0.7;
  auto diag = run({line(Vector3d(1, 2, 3), Vector3d(-7.3, 11.1, -4.2))}, fine);
  EXPECT_LE(max_gap(diag), 0.7 + 1e-12);
  const double len = (Vector3d(-7.3, 11.1, -4.2) - Vector3d(1, 2, 3)).norm();
  EXPECT_EQ(diag.size(), 1u + static_cast<std::size_t>(std::ceil(len / 0.7)));
}

TEST(Fragmenter, EndPointsAreBitExactAndStartOnlyOnce) {
  // Coordinates that are not representable exactly, so interpolation at t = 1
  // would not reproduce them.
  const Vector3d p0(0.1, 0.2, -0.3), p1(-123.456789, 0.1 + 0.2, -7.77777777),
      p2(-3.3333333333, -99.9999999, -0.7);
  std::vector<Motion> motions{line(p0, p1), line(p1, p2, 0.0)};
  Fragmenter fragmenter({});
  std::vector<PathPoint> pts;
  std::vector<std::size_t> ends;
  for (const auto& m : motions) {
    fragmenter.add(m, [&](const PathPoint& p) { pts.push_back(p); });
    ends.push_back(pts.size() - 1);
  }
  EXPECT_EQ(pts.front().p, p0);
  EXPECT_EQ(pts[ends[0]].p, p1);  // Eigen == is exact comparison
  EXPECT_EQ(pts[ends[1]].p, p2);
  // The start of the second motion is not repeated.
  EXPECT_NE(pts[ends[0] + 1].p, p1);
  EXPECT_EQ(fragmenter.points(), pts.size());
}

TEST(Fragmenter, QuarterArcPointsLieOnTheCircle) {
  const Vector3d c(-500.0, -250.0, -280.0);
  const double r = 50.0;
  const Vector3d a = c + Vector3d(r, 0, 0), b = c + Vector3d(0, r, 0);
  auto pts = run({arc(a, b, c, 1)});
  const double len = r * kPi / 2.0;
  ASSERT_EQ(pts.size(), 1u + static_cast<std::size_t>(std::ceil(len / 5.0)));
  EXPECT_EQ(pts.back().p, b);
  for (const auto& p : pts) {
    EXPECT_NEAR((p.p - c).head<2>().norm(), r, 1e-9);
    EXPECT_EQ(p.p.z(), c.z());
    EXPECT_EQ(p.kind, MotionKind::arc);
    // Counter-clockwise quarter from +x to +y stays in the first quadrant.
    EXPECT_GE(p.p.x() - c.x(), -1e-9);
    EXPECT_GE(p.p.y() - c.y(), -1e-9);
  }
  // Equal arc length: all chords equal and below the step.
  for (std::size_t i = 2; i < pts.size(); ++i)
    EXPECT_NEAR((pts[i].p - pts[i - 1].p).norm(), (pts[1].p - pts[0].p).norm(), 1e-9);
  EXPECT_LE(max_gap(pts), 5.0);
}

TEST(Fragmenter, ClockwiseArcGoesTheOtherWay) {
  const Vector3d c(0, 0, 0), a(10, 0, 0), b(0, 10, 0);
  auto pts = run({arc(a, b, c, -1)});  // three quarters, through (0, -10) and (-10, 0)
  const double len = 10.0 * 1.5 * kPi;
  ASSERT_EQ(pts.size(), 1u + static_cast<std::size_t>(std::ceil(len / 5.0)));
  bool passed_negative_y = false;
  for (const auto& p : pts) {
    EXPECT_NEAR(p.p.norm(), 10.0, 1e-9);
    if (p.p.y() < -9.0) passed_negative_y = true;
  }
  EXPECT_TRUE(passed_negative_y);
}

// Half circles in each plane: rotation > 0 is counter-clockwise seen from the
// + end of the normal axis, so the midpoint lies on the + side of b where
// (a, b, n) = XY: (x, y, z), XZ: (z, x, y), YZ: (y, z, x).
TEST(Fragmenter, ArcPlanesFollowRightHandRule) {
  struct Case {
    Plane plane;
    int a, b, n;
  };
  for (const Case& k :
       {Case{Plane::xy, 0, 1, 2}, Case{Plane::xz, 2, 0, 1}, Case{Plane::yz, 1, 2, 0}}) {
    const Vector3d c(-400.0, -200.0, -150.0);
    Vector3d s = c, e = c;
    s[k.a] += 20.0;
    e[k.a] -= 20.0;
    for (int rotation : {1, -1}) {
      auto pts = run({arc(s, e, c, rotation, k.plane)});
      const PathPoint& mid = pts[pts.size() / 2];
      EXPECT_NEAR(mid.p[k.b] - c[k.b], rotation * 20.0, 0.2)
          << "plane " << static_cast<int>(k.plane) << " rotation " << rotation;
      for (const auto& p : pts) {
        EXPECT_EQ(p.p[k.n], c[k.n]);
        EXPECT_NEAR(std::hypot(p.p[k.a] - c[k.a], p.p[k.b] - c[k.b]), 20.0, 1e-9);
      }
    }
  }
}

TEST(Fragmenter, HelixWithExtraTurnsIsSplitByArcLength) {
  const Vector3d c(-300.0, -200.0, -100.0);
  const double r = 8.0, h = -12.0;
  const Vector3d a = c + Vector3d(r, 0, 0);
  const Vector3d b = c + Vector3d(r, 0, h);  // full circle (same x, y) plus 2 extra turns
  auto pts = run({arc(a, b, c, 3)});
  const double sweep = 3 * 2 * kPi;
  const double len = std::hypot(r * sweep, h);
  ASSERT_EQ(pts.size(), 1u + static_cast<std::size_t>(std::ceil(len / 5.0)));
  EXPECT_EQ(pts.back().p, b);
  // Unwrap the angle: three full turns counter-clockwise.
  double total = 0.0;
  for (std::size_t i = 1; i < pts.size(); ++i) {
    const Vector3d u = pts[i - 1].p - c, v = pts[i].p - c;
    total += std::atan2(u.x() * v.y() - u.y() * v.x(), u.x() * v.x() + u.y() * v.y());
    EXPECT_NEAR(std::hypot(v.x(), v.y()), r, 1e-9);
    // z moves linearly with the angle.
    const double t = static_cast<double>(i) / static_cast<double>(pts.size() - 1);
    EXPECT_NEAR(pts[i].p.z(), c.z() + h * t, 1e-9);
    EXPECT_EQ(pts[i].dir[2], -1);
  }
  EXPECT_NEAR(total, sweep, 1e-9);
  EXPECT_LE(max_gap(pts), 5.0);

  ArcSpan span(arc(a, b, c, 3));
  EXPECT_NEAR(span.length(), len, 1e-12);
  EXPECT_NEAR(span.sweep(), sweep, 1e-12);
}

TEST(Fragmenter, FullCircleAndClockwiseTurns) {
  const Vector3d c(0, 0, 0), a(0, -5, 0);
  ArcSpan full(arc(a, a, c, -1));
  EXPECT_NEAR(full.sweep(), -2 * kPi, 1e-12);
  ArcSpan turns(arc(a, a, c, -2));
  EXPECT_NEAR(turns.sweep(), -4 * kPi, 1e-12);
  auto pts = run({arc(a, a, c, -1)});
  ASSERT_EQ(pts.size(), 1u + static_cast<std::size_t>(std::ceil(10.0 * kPi / 5.0)));
  EXPECT_EQ(pts.back().p, a);
}

TEST(Fragmenter, ArcSampleMatchesPointAndVelocity) {
  const ArcSpan span(arc(Vector3d(3, 4, 1), Vector3d(-4, 3, 2), Vector3d(0, 0, 1), -2, Plane::xy));
  for (double t : {0.0, 0.125, 0.5, 0.9, 1.0}) {
    Vector3d p, v;
    span.sample(t, p, v);
    EXPECT_TRUE(p.isApprox(span.point(t), 1e-14)) << t;
    EXPECT_TRUE(v.isApprox(span.velocity(t), 1e-14)) << t;
  }
  Vector3d p, v;
  span.sample(1.0, p, v);
  EXPECT_EQ(p, Vector3d(-4, 3, 2));
}

TEST(Fragmenter, IncrementalArcSamplesMatchDirectSamples) {
  // A long helix with a changing radius: 1000 samples by rotation recurrence.
  const ArcSpan span(arc(Vector3d(-400, -250, -300), Vector3d(-400, -250.01, -340),
                         Vector3d(-450, -250, -300), -5, Plane::xy));
  std::size_t calls = 0;
  double worst = 0.0;
  span.for_each_sample(1000, [&](std::size_t i, const Vector3d& p, const Vector3d& v) {
    ++calls;
    Vector3d p_ref, v_ref;
    span.sample(static_cast<double>(i) / 1000.0, p_ref, v_ref);
    worst = std::max(worst, (p - p_ref).norm());
    EXPECT_TRUE(v.isApprox(v_ref, 1e-12)) << i;
    if (i == 1000) {
      EXPECT_EQ(p, Vector3d(-400, -250.01, -340));
    }
  });
  EXPECT_EQ(calls, 1000u);
  EXPECT_LT(worst, 1e-10);
}

TEST(Fragmenter, EndOffTheCircleIsReachedByLinearRadius) {
  // End radius 50.002 instead of 50 (within an interpreter's tolerance).
  const Vector3d c(0, 0, 0), a(50, 0, 0), b(-50.002, 0, 0);
  ArcSpan span(arc(a, b, c, 1));
  EXPECT_NEAR(span.start_radius(), 50.0, 1e-12);
  EXPECT_NEAR(span.end_radius(), 50.002, 1e-12);
  auto pts = run({arc(a, b, c, 1)});
  EXPECT_EQ(pts.back().p, b);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const double t = static_cast<double>(i) / static_cast<double>(pts.size() - 1);
    EXPECT_NEAR(pts[i].p.norm(), 50.0 + 0.002 * t, 1e-9);
  }
}

TEST(Fragmenter, StepBoundHoldsWhileTheRadiusChanges) {
  // Radius 10 → 10.02 over a half circle; a step that divides the mean-radius
  // length exactly would let the last segments (larger radius) exceed it.
  const Vector3d c(0, 0, 0), a(10, 0, 0), b(-10.02, 0, 0);
  FragmentOptions options;
  options.step = ArcSpan(arc(a, b, c, 1)).length() / 100.0;
  auto pts = run({arc(a, b, c, 1)}, options);
  EXPECT_LE(max_gap(pts), options.step);
  EXPECT_EQ(pts.back().p, b);
}

TEST(Fragmenter, DirectionsAreSignsOfTheLastMotionOfEachAxis) {
  const Vector3d p0(0, 0, 0), p1(10, 0, 0), p2(10, -10, 0);
  auto pts = run({line(p0, p1), line(p1, p2)});
  using Dir = std::array<std::int8_t, 3>;
  EXPECT_EQ(pts.front().dir, (Dir{0, 0, 0}));  // nothing has moved yet
  EXPECT_EQ(pts[1].dir, (Dir{1, 0, 0}));
  EXPECT_EQ(pts.back().dir, (Dir{1, -1, 0}));  // x keeps its last sign

  // Counter-clockwise quarter from (10, 0) to (0, 10): x falls, y rises; at the
  // end the y velocity is zero and y keeps +1. Then a clockwise half circle
  // from (0, 10) about (0, 0) through (10, 0) to (0, -10): x rises, then falls;
  // y falls throughout.
  const Vector3d c(0, 0, 0), a(10, 0, 0), b(0, 10, 0), e(0, -10, 0);
  Fragmenter fragmenter({});
  std::vector<PathPoint> q, h;
  fragmenter.add(arc(a, b, c, 1), [&](const PathPoint& p) { q.push_back(p); });
  fragmenter.add(arc(b, e, c, -1), [&](const PathPoint& p) { h.push_back(p); });
  for (std::size_t i = 1; i < q.size(); ++i) EXPECT_EQ(q[i].dir, (Dir{-1, 1, 0})) << i;
  for (std::size_t i = 0; i < h.size(); ++i) {
    if (h[i].p.y() > 0.5) {
      EXPECT_EQ(h[i].dir[0], 1) << i;
    }
    if (h[i].p.y() < -0.5) {
      EXPECT_EQ(h[i].dir[0], -1) << i;
    }
    EXPECT_EQ(h[i].dir[1], -1) << i;
  }
  // At (0, -10) the x velocity is -, the y velocity is zero: y keeps -1.
  EXPECT_EQ(h.back().dir, (Dir{-1, -1, 0}));

  // A half circle whose x velocity changes sign in the middle.
  auto half = run({arc(Vector3d(0, -10, 0), Vector3d(0, 10, 0), c, 1)});
  for (std::size_t i = 1; i < half.size(); ++i) {
    const double y = half[i].p.y();
    if (y < -1.0) {
      EXPECT_EQ(half[i].dir[0], 1) << i;
    }
    if (y > 1.0) {
      EXPECT_EQ(half[i].dir[0], -1) << i;
    }
    EXPECT_EQ(half[i].dir[1], 1) << i;
  }
}

TEST(Fragmenter, TimesFollowFeedsRapidRateAndDwells) {
  FragmentOptions options;
  options.rapid_rate = 6000.0;  // 100 mm/s
  Fragmenter fragmenter(options);
  std::vector<PathPoint> pts;
  auto sink = [&](const PathPoint& p) { pts.push_back(p); };
  fragmenter.add(line(Vector3d(0, 0, 0), Vector3d(100, 0, 0), 0.0), sink);  // rapid: 1 s
  EXPECT_NEAR(pts.back().time, 1.0, 1e-12);
  EXPECT_EQ(pts.back().kind, MotionKind::rapid);
  fragmenter.add(line(Vector3d(100, 0, 0), Vector3d(100, 30, 0), 600.0), sink);  // 10 mm/s: 3 s
  EXPECT_NEAR(pts.back().time, 4.0, 1e-12);
  EXPECT_NEAR(pts[pts.size() - 2].time, 4.0 - 0.5, 1e-12);  // 5 mm before the end
  Motion dwell;
  dwell.kind = MotionKind::dwell;
  dwell.start = dwell.end = Vector3d(100, 30, 0);
  dwell.dwell_seconds = 2.5;
  const std::size_t before = pts.size();
  fragmenter.add(dwell, sink);
  EXPECT_EQ(pts.size(), before);  // a dwell emits no point
  EXPECT_NEAR(fragmenter.time(), 6.5, 1e-12);
  // Half circle r = 10 at 1200 mm/min (20 mm/s): 10π mm in π/2 s.
  fragmenter.add(
      arc(Vector3d(100, 30, 0), Vector3d(100, 50, 0), Vector3d(100, 40, 0), 1, Plane::xy, 1200.0),
      sink);
  EXPECT_NEAR(pts.back().time, 6.5 + kPi / 2.0, 1e-9);
  for (std::size_t i = 1; i < pts.size(); ++i) EXPECT_GT(pts[i].time, pts[i - 1].time);
  EXPECT_EQ(pts.front().time, 0.0);
}

TEST(Fragmenter, ZeroLengthMotionsEmitNothingNew) {
  const Vector3d p(-10, -20, -30);
  auto pts = run({line(p, p), arc(p, p, p, 1), line(p, p, 0.0)});
  ASSERT_EQ(pts.size(), 1u);  // only the start point of the program
  EXPECT_EQ(pts[0].p, p);
  EXPECT_EQ(pts[0].time, 0.0);

  Motion dwell;
  dwell.kind = MotionKind::dwell;
  auto none = run({dwell});
  EXPECT_TRUE(none.empty());
}

TEST(Fragmenter, PointsCarryLineFeedAndToolLength) {
  auto pts = run({line(Vector3d(0, 0, 0), Vector3d(12, 0, 0), 450.0, 17)});
  for (const auto& p : pts) {
    EXPECT_EQ(p.line, 17u);
    EXPECT_EQ(p.feed, 450.0);
    EXPECT_EQ(p.tool_length, 200.0);
    EXPECT_EQ(p.kind, MotionKind::linear);
  }
}

TEST(Fragmenter, RejectsBadOptionsAndArcsWithoutRotation) {
  FragmentOptions bad;
  bad.step = 0.0;
  EXPECT_THROW(Fragmenter{bad}, std::invalid_argument);
  bad.step = std::nan("");
  EXPECT_THROW(Fragmenter{bad}, std::invalid_argument);
  FragmentOptions slow;
  slow.rapid_rate = -1.0;
  EXPECT_THROW(Fragmenter{slow}, std::invalid_argument);
  EXPECT_THROW(run({arc(Vector3d(1, 0, 0), Vector3d(0, 1, 0), Vector3d::Zero(), 0)}),
               std::invalid_argument);
}

}  // namespace
}  // namespace abbe::path
