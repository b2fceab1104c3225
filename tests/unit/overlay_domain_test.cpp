// An overlay knows the box and time window it was fitted on
// (overlay_domain.hpp): inside, nothing changes bit for bit; outside, its
// polynomial, smooth and time terms equal their value on the boundary (never
// extrapolated) while linear and periodic terms are evaluated as written;
// points outside are counted for one warning; an absurd correction is
// refused; the domain is written and read with the overlay, and an overlay
// without one says its domain is unknown.
#include "abbe/diagnose/overlay_domain.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "abbe/diagnose/overlay.hpp"
#include "abbe/diagnose/overlay_extension.hpp"
#include "abbe/io/input_error.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/model/error_model.hpp"

namespace abbe::diagnose {
namespace {

const std::string kSample = std::string(ABBE_SOURCE_DIR) + "/machines/sample/machine.yaml";

// A smooth function of t (degree 6 over the two-hour window 0…7200 s), a
// smooth function of (x, y), a coupling, a drift ∝ t and ∝ x·t, plus a
// scale and a cyclic term — the domain of the measurement they came from.
const char* kOverlay = R"(format: abbe-overlay-1
model: ae-arm
machine: sample
domain:
  min: [-800, -400, -300]
  max: [-100, -50, -100]
  time: [0, 7200]
effects:
  - term: unexplained
    direction: Z
    vars: [t]
    degree: 6
    lo: [-800, -400, -300, 0]
    hi: [-100, -50, -100, 7200]
    coef: [1.2, -0.8, 0.6, 0.9, -0.4, 0.7]
  - term: unexplained
    direction: Y
    vars: [x, y]
    degree: 2
    lo: [-800, -400, -300, 0]
    hi: [-100, -50, -100, 7200]
    coef: [0.5, -0.3, 0.2, 0.4, 0.1, -0.6, 0.3, 0.2]
  - term: coupling
    axis: X
    with: Y
    direction: Z
    centre: [-450, -225, -200]
    half: [350, 175, 100]
    coef: [2.5]
  - term: thermal_drift
    axis: X
    direction: X
    tau_s: 0
    coef: [1.5]
  - term: thermal_drift
    axis: Y
    direction: Y
    tau_s: 1800
    with: X
    coef: [-3]
  - term: scale
    axis: X
    direction: X
    coef: [10]
  - term: cyclic
    axis: Y
    direction: Y
    period_mm: 16
    coef: [0.4, -0.2]
)";

PointContext at(double x, double y, double z, double t) {
  PointContext pc;
  pc.s = Eigen::Vector3d(x, y, z);
  pc.p = pc.s;
  pc.t = t;
  pc.dir = {1, -1, 1};
  return pc;
}

Overlay parsed() { return Overlay::parse(kOverlay, "domain.yaml"); }

TEST(OverlayDomain, ReadAndWrittenWithTheOverlay) {
  const Overlay ov = parsed();
  ASSERT_TRUE(ov.domain.known);
  EXPECT_EQ(ov.domain.lo, Eigen::Vector3d(-800, -400, -300));
  EXPECT_EQ(ov.domain.hi, Eigen::Vector3d(-100, -50, -100));
  EXPECT_EQ(ov.domain.t_lo, 0.0);
  EXPECT_EQ(ov.domain.t_hi, 7200.0);
  EXPECT_EQ(ov.file, "domain.yaml");
  const Overlay again = Overlay::parse(ov.to_yaml(), "again.yaml");
  ASSERT_TRUE(again.domain.known);
  EXPECT_EQ(again.domain.lo, ov.domain.lo);
  EXPECT_EQ(again.domain.hi, ov.domain.hi);
  EXPECT_EQ(again.domain.t_hi, ov.domain.t_hi);
  const PointContext pc = at(-2000, 300, 500, 1e6);  // far outside: clamped alike
  EXPECT_EQ(again.evaluate(pc), ov.evaluate(pc));
}

TEST(OverlayDomain, InsideTheBoxNothingChangesBitForBit) {
  const Overlay ov = parsed();
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 2000; ++i) {
    // Corners and faces included (u = 0 or 1 exactly).
    auto pick = [&](double lo, double hi) {
      const double r = u(rng);
      return r < 0.05 ? lo : r > 0.95 ? hi : lo + (hi - lo) * u(rng);
    };
    const PointContext pc =
        at(pick(-800, -100), pick(-400, -50), pick(-300, -100), pick(0.0, 7200.0));
    ASSERT_TRUE(ov.domain.contains(pc, true));
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const Term& t : ov.terms) sum += t.evaluate(pc);
    ASSERT_EQ(ov.evaluate(pc), sum);  // exact
    const PointContext c = ov.domain.clamp(pc);
    ASSERT_EQ(c.s, pc.s);
    ASSERT_EQ(c.p, pc.p);
    ASSERT_EQ(c.t, pc.t);
  }
}

TEST(OverlayDomain, OutsideClampedTermsEqualTheBoundaryValue) {
  const Overlay ov = parsed();
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> x(-3000, 2000), t(-5e4, 5e5);
  for (int i = 0; i < 2000; ++i) {
    const PointContext pc = at(x(rng), x(rng), x(rng), t(rng));
    // The boundary point, by hand.
    const PointContext b =
        at(std::clamp(pc.s.x(), -800.0, -100.0), std::clamp(pc.s.y(), -400.0, -50.0),
           std::clamp(pc.s.z(), -300.0, -100.0), std::clamp(pc.t, 0.0, 7200.0));
    Eigen::Vector3d expected = Eigen::Vector3d::Zero();
    for (const Term& term : ov.terms) {
      const bool linear = term.kind == TermKind::scale || term.kind == TermKind::cyclic;
      expected += term.evaluate(linear ? pc : b);
    }
    ASSERT_EQ(ov.evaluate(pc), expected);
    // The clamped terms alone are bounded by their largest value in the domain.
    EXPECT_LT(ov.evaluate(pc).norm(), 10e-3 * 3000 + 20.0);
  }
}

// The issue's case: a smooth function of time fitted over a two-hour
// campaign, evaluated along a program whose clock runs far beyond it.
TEST(OverlayDomain, ATimeTermOutsideItsWindowPredictsNoMetres) {
  Overlay ov = parsed();
  Overlay old = ov;
  old.domain = OverlayDomain{};  // as an overlay written before domains
  const PointContext late = at(-400, -200, -200, 1e5);
  const PointContext end = at(-400, -200, -200, 7200);
  // Without a domain the degree-6 polynomial explodes (metres).
  EXPECT_GT(std::abs(old.terms[0].evaluate(late).z()), 1e6);
  // With it, the value at the end of the window.
  EXPECT_EQ(ov.evaluate(late), ov.evaluate(end));
  EXPECT_LT(ov.evaluate(late).norm(), 30.0);
}

TEST(OverlayDomain, ExtensionCountsPointsOutsideAndWarnsOnce) {
  const machine::Machine m = machine::Machine::load(kSample);
  const auto ext = std::make_shared<const OverlayExtension>(parsed(), m);
  const model::ErrorModel extended =
      model::ErrorModel(m, model::ModelKind::ae_arm).with_extension(ext);
  model::ModelData data;
  model::EvalPoint p;
  p.p = Eigen::Vector3d(-400, -200, -200);
  for (double time : {0.0, 3600.0, 7200.0}) {
    p.time = time;
    extended.evaluate(p, data);
  }
  EXPECT_EQ(ext->evaluations(), 3u);
  EXPECT_EQ(ext->outside(), 0u);
  EXPECT_EQ(ext->domain_warning(), "");
  p.time = 9000.0;  // after the window
  extended.evaluate(p, data);
  p.time = 100.0;
  p.p.x() = -50.0;  // 50 mm beyond the box
  extended.evaluate(p, data);
  EXPECT_EQ(ext->outside(), 2u);
  const std::string w = ext->domain_warning();
  EXPECT_NE(w.find("domain.yaml: 2 of 5 evaluations outside"), std::string::npos) << w;
  EXPECT_NE(ext->domain_warning(1).find("domain.yaml: 2 of 5 points outside"), std::string::npos);
  EXPECT_NE(w.find("up to 50 mm beyond the box, 1800 s outside the time window"), std::string::npos)
      << w;
  EXPECT_NE(w.find("t 0…7200 s"), std::string::npos) << w;
}

TEST(OverlayDomain, AnOverlayWithoutADomainSaysSo) {
  const machine::Machine m = machine::Machine::load(kSample);
  Overlay ov = parsed();
  ov.domain = OverlayDomain{};
  EXPECT_FALSE(Overlay::parse(ov.to_yaml(), "old.yaml").domain.known);
  const OverlayExtension ext(Overlay::parse(ov.to_yaml(), "old.yaml"), m);
  EXPECT_NE(ext.domain_warning().find("old.yaml: the overlay records no domain"),
            std::string::npos);
  EXPECT_NE(ext.domain_warning().find("its domain is unknown"), std::string::npos);
}

TEST(OverlayDomain, AbsurdCorrectionsAreRefused) {
  const machine::Machine m = machine::Machine::load(kSample);
  const char* huge = R"(format: abbe-overlay-1
effects:
  - term: scale
    axis: X
    direction: X
    coef: [1e7]
)";
  const auto ext = std::make_shared<const OverlayExtension>(Overlay::parse(huge, "huge.yaml"), m);
  const model::ErrorModel extended =
      model::ErrorModel(m, model::ModelKind::ae_arm).with_extension(ext);
  model::ModelData data;
  model::EvalPoint p;
  p.p = Eigen::Vector3d(-400, -200, -200);  // 1e7 ppm · 400 mm = 4 m
  try {
    extended.evaluate(p, data);
    FAIL() << "an absurd correction was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "huge.yaml");
    EXPECT_NE(e.message().find("beyond the 1000 µm an overlay may correct, refused"),
              std::string::npos)
        << e.message();
  }
  p.p.x() = -0.05;  // 0.5 mm: accepted
  EXPECT_NEAR(extended.evaluate(p, data).e_um.x() -
                  model::ErrorModel(m, model::ModelKind::ae_arm).evaluate(p, data).e_um.x(),
              -500.0, 1e-6);
  // Not finite: refused.
  Overlay nan = Overlay::parse(huge, "nan.yaml");
  nan.terms[0].coef[0] = std::numeric_limits<double>::quiet_NaN();
  const OverlayExtension nan_ext(nan, m);
  EXPECT_THROW(nan_ext.extra_um(p, {}, data), InputError);
}

TEST(OverlayDomain, BadDomainsNameTheLine) {
  auto message = [](const std::string& text) {
    try {
      Overlay::parse(text, "bad.yaml");
    } catch (const InputError& e) {
      return format_input_error(e.where(), e.message());
    }
    return std::string("accepted");
  };
  const std::string head = "format: abbe-overlay-1\ndomain:\n";
  EXPECT_NE(message(head + "  min: [0, 0, 0]\n  max: [1, 1]\n  time: [0, 1]\n").find("bad.yaml:4"),
            std::string::npos);
  EXPECT_NE(message(head + "  min: [0, 0, 0]\n  max: [1, -1, 1]\n  time: [0, 1]\n")
                .find("max -1 is below min 0 (Y)"),
            std::string::npos);
  EXPECT_NE(message(head + "  min: [0, 0, 0]\n  max: [1, 1, 1]\n").find("time"), std::string::npos);
  EXPECT_NE(
      message(head + "  min: [0, 0, 0]\n  max: [1, 1, 1]\n  time: [5, 1]\n").find("bad.yaml:5"),
      std::string::npos);
  EXPECT_NE(message(head + "  min: [0, 0, 0]\n  max: [1, 1, 1]\n  time: [0, 1]\n  when: 3\n")
                .find("when"),
            std::string::npos);
}

TEST(OverlayDomain, MergedHoldsBoth) {
  OverlayDomain a, b;
  a.known = b.known = true;
  a.lo = Eigen::Vector3d(0, 0, 0);
  a.hi = Eigen::Vector3d(1, 1, 1);
  b.lo = Eigen::Vector3d(-1, 0.5, 0.5);
  b.hi = Eigen::Vector3d(0.5, 2, 0.7);
  a.t_hi = 10;
  b.t_lo = 5;
  b.t_hi = 20;
  const OverlayDomain m = a.merged(b);
  EXPECT_EQ(m.lo, Eigen::Vector3d(-1, 0, 0));
  EXPECT_EQ(m.hi, Eigen::Vector3d(1, 2, 1));
  EXPECT_EQ(m.t_lo, 0.0);
  EXPECT_EQ(m.t_hi, 20.0);
  EXPECT_FALSE(a.merged(OverlayDomain{}).known);
}

}  // namespace
}  // namespace abbe::diagnose
