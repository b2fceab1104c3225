// The truth machine of the virtual machine: chain sets U(j), the exact
// composition against an independent 4×4 implementation, the DESIGN worked
// examples, first-order convergence, and the injected effects.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <stdexcept>

#include "abbe/sim/truth_machine.hpp"

namespace abbe::sim {
namespace {

ErrorComponent constant(double v) {
  ErrorComponent e;
  e.poly = {v};
  return e;
}

TruthMachine zero_machine() {
  TruthMachine t;
  for (auto& a : t.axes) {
    a.travel_min = -1000.0;
    a.travel_max = 0.0;
  }
  return t;
}

TEST(SimChain, CarriedAxes) {
  const auto c = ChainLayout::parse("w X' b Y Z t");
  EXPECT_TRUE(c.workpiece_side(0));
  EXPECT_FALSE(c.moves(0, 0));
  EXPECT_FALSE(c.moves(0, 1));
  EXPECT_TRUE(c.moves(1, 0) && c.moves(1, 1) && !c.moves(1, 2));
  EXPECT_TRUE(c.moves(2, 0) && c.moves(2, 1) && c.moves(2, 2));
  const auto d = ChainLayout::parse("w Y' X' b Z t");
  EXPECT_TRUE(d.moves(0, 1));   // X' carries Y'
  EXPECT_FALSE(d.moves(1, 0));  // U(Y) = {}
  EXPECT_FALSE(d.moves(1, 1));
  EXPECT_TRUE(d.moves(2, 0) && d.moves(2, 1) && d.moves(2, 2));
  const auto e = ChainLayout::parse("wbXYZt");
  EXPECT_TRUE(e.moves(1, 0) && !e.moves(0, 1));
  EXPECT_EQ(e.order()[0], 0);
}

TEST(SimChain, RejectsBadChains) {
  for (const char* bad : {"w X b Y t", "w X' b Y' Z t", "X w b Y Z t", "w X Y Z t", "w X b b Y Z t",
                          "w X' b Y Z q t", "w X X b Z t"})
    EXPECT_THROW(ChainLayout::parse(bad), std::invalid_argument) << bad;
}

TEST(SimTruth, ZeroMachineZeroDeviation) {
  const TruthMachine t = zero_machine();
  TipState tip;
  tip.p = {-300.0, -200.0, -250.0};
  tip.tool_length = 200.0;
  tip.dir = {1, -1, 1};
  EXPECT_EQ(t.deviation_um(tip), Eigen::Vector3d::Zero());
}

TEST(SimTruth, SquarenessExample3) {
  TruthMachine t = zero_machine();
  t.squareness = {14.569, -24.362, 13.757};
  TipState tip;
  tip.p = {-300.0, -200.0, -250.0};
  const Eigen::Vector3d d = t.deviation_um(tip);
  EXPECT_NEAR(d.x(), 9.004, 5e-4);
  EXPECT_NEAR(d.y(), 3.439, 5e-4);
  EXPECT_NEAR(d.z(), 0.0, 1e-12);
}

// DESIGN example 1: table axis X, EBX = 10 µrad, M = (−800, −256, −478); with the
// pivot at M the reading there is zero and the truth is the ae-arm value.
TEST(SimTruth, WorkedExample1TableAxis) {
  TruthMachine t = zero_machine();
  t.axes[0].components[4] = constant(10.0);
  t.axes[0].pivot0 = {-800.0, -256.0, -478.0};
  TipState tip;
  tip.p = {-300.0, -200.0, -250.0};
  tip.tool_length = 130.0;
  const Eigen::Vector3d d = t.deviation_um(tip);
  EXPECT_NEAR(d.x(), 2.28, 1e-4);
  EXPECT_NEAR(d.y(), 0.0, 1e-9);
  EXPECT_NEAR(d.z(), -5.00, 1e-4);
  // The laser reading at M is zero, at the tip it is the deviation.
  const Eigen::Vector3d s = TruthMachine::axis_positions(tip.p, tip.tool_length);
  EXPECT_LT(t.laser_linear_reading_um(0, s, 0, t.axes[0].pivot0).norm(), 1e-12);
}

// DESIGN example 2: tool-side Y, EAY = 20 µrad, optic at (−500, y, −300) while
// measured with the tip at x = −500, z = −280: arm (0, 0, 50) → (0, −1.00, 0).
TEST(SimTruth, WorkedExample2ToolSideAxis) {
  TruthMachine t = zero_machine();
  t.axes[1].components[3] = constant(20.0);
  const double L = 130.0;
  const Eigen::Vector3d m_meas(-500.0, -250.0, -300.0);
  const Eigen::Vector3d s_meas = TruthMachine::axis_positions({-500.0, -250.0, -280.0}, L);
  // C_Y(s) = pivot0 + s_x·e_x + s_y·e_y equals M at the measured configuration.
  t.axes[1].pivot0 = m_meas - Eigen::Vector3d(s_meas.x(), s_meas.y(), 0.0);
  TipState tip;
  tip.p = {-300.0, -200.0, -250.0};
  tip.tool_length = L;
  const Eigen::Vector3d d = t.deviation_um(tip);
  EXPECT_NEAR(d.x(), 0.0, 1e-9);
  EXPECT_NEAR(d.y(), -1.00, 1e-5);
  EXPECT_NEAR(d.z(), 0.0, 1e-4);
}

// Independent implementation: 4×4 rigid transforms with Eigen::AngleAxis.
Eigen::Vector3d composed_4x4(const TruthMachine& t, const TipState& tip) {
  const Eigen::Vector3d s = TruthMachine::axis_positions(tip.p, tip.tool_length);
  Eigen::Vector3d p = tip.p;
  for (int k = 2; k >= 0; --k) {
    const int j = t.chain.order()[static_cast<std::size_t>(k)];
    const int dir = tip.dir[static_cast<std::size_t>(j)];
    const Eigen::Vector3d theta = 1e-6 * t.rotation_urad(j, s[j], dir);
    Eigen::Affine3d e = Eigen::Affine3d::Identity();
    const Eigen::Vector3d c = t.pivot(j, s);
    e.translate(c + 1e-3 * t.translation_um(j, s[j], dir));
    if (theta.norm() > 0) e.rotate(Eigen::AngleAxisd(theta.norm(), theta.normalized()));
    e.translate(-c);
    p = e * p;
  }
  return 1e3 * (p - tip.p);
}

TruthMachine busy_machine(double angular) {
  TruthMachine t = zero_machine();
  for (int j = 0; j < 3; ++j) {
    auto& a = t.axes[static_cast<std::size_t>(j)];
    a.pivot0 = Eigen::Vector3d(-100.0 * j, 50.0 * j, 200.0 + 100.0 * j);
    for (int c = 0; c < 6; ++c) {
      ErrorComponent e;
      e.centre = -500.0;
      e.half_range = 500.0;
      const double scale = c < 3 ? 5.0 : angular;
      e.poly = {scale * 0.3 * (c - 2), scale * 0.5, -scale * 0.4 * (j - 1)};
      e.waves = {{0.2 * scale, 180.0 + 20.0 * c, 0.3 * j}};
      e.reversal = c < 3 ? 1.5 : 0.1 * angular;
      a.components[static_cast<std::size_t>(c)] = e;
    }
  }
  return t;
}

TEST(SimTruth, ExactCompositionMatchesIndependent4x4) {
  for (const char* chain : {"w X' b Y Z t", "w b X Y Z t", "w Y' X' b Z t", "w Z' Y' X' b t"}) {
    TruthMachine t = busy_machine(2000.0);  // mrad-size angles: order and exactness matter
    t.chain = ChainLayout::parse(chain);
    for (int k = 0; k < 5; ++k) {
      TipState tip;
      tip.p = {-100.0 - 170.0 * k, -50.0 - 90.0 * k, -300.0 + 40.0 * k};
      tip.tool_length = 150.0;
      tip.dir = {k % 2 ? 1 : -1, 1, k % 3 ? -1 : 1};
      const Eigen::Vector3d a = t.geometric_deviation_um(tip);
      const Eigen::Vector3d b = composed_4x4(t, tip);
      EXPECT_LT((a - b).norm(), 1e-7) << chain << " " << a.transpose() << " vs " << b.transpose();
    }
  }
}

// One axis: exact E_j(P) − P vs the first-order ae-arm formula δ(M) + θ × (P − M);
// the difference is second order, so it scales as λ².
TEST(SimTruth, FirstOrderErrorConvergesQuadratically) {
  const Eigen::Vector3d m(-800.0, -256.0, -478.0);
  TipState tip;
  tip.p = {-300.0, -200.0, -250.0};
  tip.tool_length = 200.0;
  double previous = 0.0;
  for (double lambda : {8.0, 4.0, 2.0, 1.0}) {
    TruthMachine t = zero_machine();
    const double th[3] = {30.0, -20.0, 25.0};
    for (int c = 0; c < 3; ++c) {
      t.axes[0].components[static_cast<std::size_t>(c)] = constant(2.0 + c);
      t.axes[0].components[static_cast<std::size_t>(3 + c)] = constant(lambda * th[c]);
    }
    t.axes[0].pivot0 = {-495.0, -250.0, -600.0};
    const Eigen::Vector3d s = TruthMachine::axis_positions(tip.p, tip.tool_length);
    const Eigen::Vector3d delta = t.laser_linear_reading_um(0, s, 0, m);
    const Eigen::Vector3d theta = t.rotation_urad(0, s.x(), 0);
    const Eigen::Vector3d first = delta + 1e-3 * theta.cross(tip.p - m);
    const double err = (t.deviation_um(tip) - first).norm();
    EXPECT_GT(err, 0.0);
    if (previous > 0.0) {
      EXPECT_NEAR(previous / err, 4.0, 0.05) << lambda;
    }
    previous = err;
  }
}

TEST(SimTruth, Effects) {
  TruthMachine t = zero_machine();
  t.axes[0].components[4] = constant(10.0);  // EBX for arm_offset
  TipState tip;
  tip.p = {-300.0, -200.0, -250.0};
  tip.tool_length = 200.0;
  tip.dir = {1, 1, 1};
  tip.set = "plate2";
  const Eigen::Vector3d base = t.deviation_um(tip);
  auto with = [&](const char* spec, TipState at) {
    TruthMachine u = t;
    u.effects = {parse_effect(spec)};
    return Eigen::Vector3d(u.deviation_um(at) - t.deviation_um(at));
  };
  TipState down = tip;
  down.dir[1] = -1;
  EXPECT_NEAR(with("reversal:Y:4um", tip).y() - with("reversal:Y:4um", down).y(), 4.0, 1e-12);
  EXPECT_NEAR(with("scale:X:20ppm", tip).x(), 20.0 * -300.0 / 1000.0, 1e-12);
  TipState later = tip;
  later.time = 1200.0;
  EXPECT_NEAR(with("thermal_drift:Z:8um:tau=1200", later).z(), 8.0 * (1.0 - std::exp(-1.0)), 1e-12);
  EXPECT_NEAR(with("thermal_drift:Z:8um:tau=1200", tip).z(), 0.0, 1e-12);  // t = 0
  // Two lags in series (τ 1200 s, lag 600 s) at t = 1200 s:
  // 1 − (1200·e^−1 − 600·e^−2)/600 = 1 − 2e^−1 + e^−2.
  EXPECT_NEAR(with("thermal_drift:Z:8um:tau=1200,lag=600", later).z(),
              8.0 * (1.0 - 2.0 * std::exp(-1.0) + std::exp(-2.0)), 1e-12);
  EXPECT_NEAR(with("thermal_drift:Z:8um:tau=1200,lag=600", tip).z(), 0.0, 1e-12);
  // lag = τ: 1 − (1 + t/τ)·e^(−t/τ) = 1 − 2/e at t = τ.
  EXPECT_NEAR(with("thermal_drift:Z:8um:tau=1200,lag=1200", later).z(),
              8.0 * (1.0 - 2.0 * std::exp(-1.0)), 1e-12);
  EXPECT_NEAR(with("cyclic:X:1.5um:period=16", tip).x(), 1.5 * std::sin(2.0 * M_PI * -300.0 / 16.0),
              1e-12);
  // coupling: u_X = (−300 + 500)/500 = 0.4, u_Y = (−200 + 500)/500 = 0.6 (travels −1000…0)
  EXPECT_NEAR(with("coupling:X:5um:with=Y,dir=Z", tip).z(), 5.0 * 0.4 * 0.6, 1e-12);
  // arm_offset: EBX × (50 mm e_z) = (10e-6·50 mm, 0, 0) = 0.5 µm in x
  EXPECT_NEAR(with("arm_offset:X:50mm:dir=Z", tip).x(), 0.5, 1e-12);
  EXPECT_NEAR(with("setup:Y:3um:set=plate2", tip).y(), 3.0, 1e-12);
  TipState other = tip;
  other.set = "plate1";
  EXPECT_EQ(with("setup:Y:3um:set=plate2", other), Eigen::Vector3d::Zero());
  // rotation about Z by 20 µrad around the origin: e_z × P = (−y, x, 0)
  const Eigen::Vector3d r = with("setup:Z:20urad", tip);
  EXPECT_NEAR(r.x(), 20e-3 * 200.0, 1e-12);
  EXPECT_NEAR(r.y(), 20e-3 * -300.0, 1e-12);
  EXPECT_EQ(t.deviation_um(tip), base);  // effects do not leak into the original
}

TEST(SimEffect, DriftWithALagIsNotAnExponential) {
  // Zero at t = 0, starts with zero slope, rises monotonically to 1; the
  // lag-free form is the exponential; τ and the lag play symmetric roles.
  EXPECT_DOUBLE_EQ(drift_fraction(0.0, 2400.0, 900.0), 0.0);
  EXPECT_DOUBLE_EQ(drift_fraction(-5.0, 2400.0, 900.0), 0.0);
  EXPECT_LT(drift_fraction(10.0, 2400.0, 900.0), 1e-4);  // exponential: 4.2e-3
  EXPECT_NEAR(drift_fraction(10.0, 2400.0, 0.0), 1.0 - std::exp(-10.0 / 2400.0), 1e-15);
  EXPECT_NEAR(drift_fraction(1e6, 2400.0, 900.0), 1.0, 1e-12);
  EXPECT_NEAR(drift_fraction(3000.0, 2400.0, 900.0), drift_fraction(3000.0, 900.0, 2400.0), 1e-12);
  EXPECT_NEAR(drift_fraction(3000.0, 2400.0, 2400.0 * (1.0 + 1e-12)),
              drift_fraction(3000.0, 2400.0, 2400.0), 1e-6);
  double prev = 0.0;
  for (double t = 60.0; t <= 20000.0; t += 60.0) {
    const double f = drift_fraction(t, 2400.0, 900.0);
    EXPECT_GT(f, prev) << t;
    prev = f;
  }
}

TEST(SimEffect, ParsesAndRejects) {
  const Effect e = parse_effect("cyclic:X:1.5um:period=12,phase=90,dir=Y");
  EXPECT_EQ(e.kind, EffectKind::cyclic);
  EXPECT_EQ(e.axis, 0);
  EXPECT_EQ(e.direction, 1);
  EXPECT_DOUBLE_EQ(e.magnitude, 1.5);
  EXPECT_DOUBLE_EQ(e.period_mm, 12.0);
  EXPECT_NEAR(e.phase_rad, M_PI / 2, 1e-15);
  EXPECT_EQ(parse_effect("thermal_drift:Z:10ppm").unit, "ppm");
  EXPECT_EQ(parse_effect("arm_offset:Y:50mm").direction, 2);
  for (const char* bad : {"reversal:Y:4", "reversal:Q:4um", "wobble:X:1um", "scale:X:4um",
                          "coupling:X:5um", "cyclic:X:1um:period=0", "cyclic:X:1um:tau=5",
                          "reversal:Y", "setup:X:abcum", "thermal_drift:Z:8um:tau=-1",
                          "thermal_drift:Z:8um:lag=-1", "cyclic:X:1um:lag=5", "reversal:Y:4um:dir"})
    EXPECT_THROW(parse_effect(bad), std::invalid_argument) << bad;
}

}  // namespace
}  // namespace abbe::sim
